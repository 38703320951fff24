-- tools/branch-cost: what a tape interpreter's dispatch costs on this driver.
function love.conf(t)
  t.window.width, t.window.height = 640, 360
  t.modules.audio, t.modules.sound = false, false
end
