function love.conf(t) t.window.width = 64 t.window.height = 64 t.window.title = "compile" t.modules.audio = false t.modules.sound = false end
