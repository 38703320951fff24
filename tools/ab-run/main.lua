-- love tools/ab-run W H FRAMES DUMP_A DUMP_B ...: the frame times of each dump's shader
-- (written by tools/ab-dump.fnl, in any checkout), drawn in turn, frame by frame, in
-- one process: the ratio of two versions of the code on a shared, noisy machine.
-- AB_COMPARE=1 also counts the pixels that differ from the first dump's picture.
-- (run from the project root: tools/send-uniforms.lua)
local send = require("tools.send-uniforms")
function love.load(args)
  local w, h, frames = tonumber(args[1]), tonumber(args[2]), tonumber(args[3])
  local vs = {}
  for i = 4, #args do
    local d = dofile(args[i])
    local shader = love.graphics.newShader(d.source)
    send(shader, d.uniforms)
    vs[#vs + 1] = {name = args[i], shader = shader, canvas = love.graphics.newCanvas(w, h), times = {}}
  end
  local function frame(v)
    local t0 = love.timer.getTime()
    love.graphics.push("all")
    love.graphics.setCanvas(v.canvas)
    love.graphics.setShader(v.shader)
    love.graphics.rectangle("fill", 0, 0, w, h)
    love.graphics.pop()
    v.canvas:newImageData(0, 1, 0, 0, 1, 1)
    return 1000 * (love.timer.getTime() - t0)
  end
  for _, v in ipairs(vs) do frame(v) end
  for r = 1, frames do for _, v in ipairs(vs) do v.times[#v.times + 1] = frame(v) end end
  -- AB_FRAMES=1: each dump's frame times in the order drawn (one line each), before
  -- the medians: ratios round by round (tools/scaling-ab.sh).
  if os.getenv("AB_FRAMES") then
    for _, v in ipairs(vs) do
      local ts = {}
      for i, t in ipairs(v.times) do ts[i] = string.format("%.2f", t) end
      print("frames " .. v.name .. " " .. table.concat(ts, " "))
    end
  end
  -- AB_COMPARE=1: each dump's picture against the first one's, pixel by pixel (the
  -- same picture from two forms of one scene, say uniforms and folded).
  if os.getenv("AB_COMPARE") then
    local first = vs[1].canvas:newImageData()
    for i = 2, #vs do
      local img = vs[i].canvas:newImageData()
      local differ, most = 0, 0
      for y = 0, h - 1 do
        for x = 0, w - 1 do
          local r1, g1, b1 = first:getPixel(x, y)
          local r2, g2, b2 = img:getPixel(x, y)
          local d = math.max(math.abs(r1 - r2), math.abs(g1 - g2), math.abs(b1 - b2)) * 255
          if d > 0.5 then differ = differ + 1 end
          if d > most then most = d end
        end
      end
      print(string.format("%s against %s: %d of %d pixels differ, largest %.0f/255",
                          vs[i].name, vs[1].name, differ, w * h, most))
    end
  end
  for _, v in ipairs(vs) do
    table.sort(v.times)
    print(string.format("%-40s median %.1f ms (min %.1f, max %.1f)", v.name, v.times[math.floor((#v.times + 1) / 2)], v.times[1], v.times[#v.times]))
  end
  if #vs == 2 then print(string.format("ratio B/A %.3f", vs[2].times[math.floor((#vs[2].times + 1) / 2)] / vs[1].times[math.floor((#vs[1].times + 1) / 2)])) end
  love.event.quit(0)
end
function love.errorhandler(msg) io.stderr:write("error: ", tostring(msg), "\n", debug.traceback(), "\n") os.exit(1) end
