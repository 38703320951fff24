;; shaders/player/despeckle.glsl, which the player runs on a picture smaller than the
;; window before stretching it (src/app/play.fnl's draw-stretched): a lone bright or
;; dark pixel is clamped to its neighbours' range, an edge and a one-pixel line keep
;; theirs. Run by LÖVE (offscreen) in a small game folder holding the shader.
(local app (require :test.support.app))

(local game-conf "
function love.conf(t) t.modules.audio = false t.modules.sound = false end
function love.errorhandler(msg) io.stderr:write('error: ' .. tostring(msg) .. '\\n') os.exit(3) end
")

(local game-main "
function love.load()
  local src = love.graphics.newCanvas(8, 8)
  love.graphics.setCanvas(src)
  love.graphics.clear(0.25, 0.25, 0.25, 1)
  love.graphics.setColor(1, 1, 1, 1)
  love.graphics.rectangle('fill', 3, 2, 1, 1)    -- a lone bright pixel at (3, 2)
  love.graphics.rectangle('fill', 0, 5, 8, 1)    -- a bright line along row 5
  love.graphics.setColor(0, 0, 0, 1)
  love.graphics.rectangle('fill', 6, 0, 1, 1)    -- a lone dark pixel at (6, 0), on the border
  love.graphics.setColor(0.75, 0.75, 0.75, 1)
  love.graphics.rectangle('fill', 0, 7, 8, 1)    -- another grey below the line: an edge
  love.graphics.setCanvas()
  local shader = love.graphics.newShader((love.filesystem.read('despeckle.glsl')))
  local dst = love.graphics.newCanvas(8, 8)
  love.graphics.setCanvas(dst)
  love.graphics.setBlendMode('replace')
  love.graphics.setShader(shader)
  shader:send('texelSize', {1 / 8, 1 / 8})
  love.graphics.setColor(1, 1, 1, 1)
  love.graphics.draw(src, 0, 0)
  love.graphics.setShader()
  love.graphics.setCanvas()
  local d = dst:newImageData()
  local function at(x, y) local r = d:getPixel(x, y); return r end
  print(string.format('speck %.3f dark %.3f line %.3f edge %.3f field %.3f',
                      at(3, 2), at(6, 0), at(4, 5), at(4, 7), at(1, 1)))
  love.event.quit(0)
end
")

(describe "despeckle"
  (fn []
    (it "clamps a lone pixel to its neighbours, keeps lines, edges and the field"
      (fn []
        (let [dir (: (io.popen "mktemp -d") :read "*l")]
          (os.execute (.. "cp shaders/player/despeckle.glsl " dir "/"))
          (with-open [f (io.open (.. dir "/main.lua") :w)] (f:write game-main))
          (with-open [f (io.open (.. dir "/conf.lua") :w)] (f:write game-conf))
          (let [(code out) (app.sh (.. "cd " dir " && SDL_VIDEODRIVER=offscreen timeout 300 love ."))]
            (os.execute (.. "rm -rf " dir))
            (assert.are.equal 0 code out)
            ;; 8-bit canvas values: 0.25 is 64/255 = 0.251.
            (assert.truthy (out:find "speck 0.251 dark 0.251 line 1.000 edge 0.749 field 0.251" 1 true) out)))))))
