-- love tools/compile-run ROUNDS W H DUMP...: the compile time of each dump's shader
-- (written by tools/compile-time.fnl or tools/ab-dump.fnl, in any checkout): newShader
-- plus the first draw at W x H with its uniforms sent (llvmpipe finishes compiling at
-- the first draw), each dump in turn, ROUNDS rounds, in one process. Each compile's
-- text ends with a comment naming its round, so no cache can serve it; run it with
-- MESA_SHADER_CACHE_DISABLE=true (tools/compile-time.fnl does), or Mesa's disk cache
-- serves a text it has seen. Prints one line per dump: median, min and max ms.
-- (run from the project root: tools/send-uniforms.lua)
local send = require("tools.send-uniforms")
local function median(xs)
  local s = {}
  for i, x in ipairs(xs) do s[i] = x end
  table.sort(s)
  local n = #s
  return n % 2 == 1 and s[(n + 1) / 2] or (s[n / 2] + s[n / 2 + 1]) / 2, s[1], s[n]
end
function love.load(args)
  local rounds, w, h = tonumber(args[1]), tonumber(args[2]), tonumber(args[3])
  local vs = {}
  for i = 4, #args do
    local d = dofile(args[i])
    vs[#vs + 1] = {name = args[i], dump = d, canvas = love.graphics.newCanvas(w, h), times = {}}
  end
  local function compile(v, round)
    local t0 = love.timer.getTime()
    local shader = love.graphics.newShader(v.dump.source .. "\n// compile-run round " .. round .. "\n")
    send(shader, v.dump.uniforms)
    love.graphics.push("all")
    love.graphics.setCanvas(v.canvas)
    love.graphics.setShader(shader)
    love.graphics.rectangle("fill", 0, 0, w, h)
    love.graphics.pop()
    v.canvas:newImageData(0, 1, 0, 0, 1, 1)
    local ms = 1000 * (love.timer.getTime() - t0)
    shader:release()
    return ms
  end
  for r = 1, rounds do
    for _, v in ipairs(vs) do v.times[#v.times + 1] = compile(v, r) end
    io.stderr:write(string.format("round %d/%d\n", r, rounds))
  end
  -- COMPILE_TIMES=1: each dump's times in the order compiled, before the medians (the
  -- ratio of two dumps round by round is steadier on a shared machine than theirs).
  if os.getenv("COMPILE_TIMES") then
    for _, v in ipairs(vs) do
      local ts = {}
      for i, t in ipairs(v.times) do ts[i] = string.format("%.0f", t) end
      print("times " .. v.name .. " " .. table.concat(ts, " "))
    end
  end
  for _, v in ipairs(vs) do
    print(string.format("compile %s median %.0f ms (min %.0f, max %.0f)", v.name, median(v.times)))
  end
  love.event.quit(0)
end
function love.errorhandler(msg) io.stderr:write("error: ", tostring(msg), "\n", debug.traceback(), "\n") os.exit(1) end
