-- MESA_SHADER_CACHE_DISABLE=true love tools/uniform-cost [N...]: what one more value
-- read by a fragment shader costs the driver's compile (newShader plus the first draw
-- at 16x16, median of 3), for N values (default 70 140 280) read four ways:
--   uniform  N elements of a vec4 uniform array, each at its constant index
--   texel    N texels of a float texture, each by texelFetch at constant coordinates
--   derived  N values made from one uniform element (uT[0] * i)
--   constant N constants
-- Each value enters a chain s = s * value + screen position, so none is dropped. On
-- llvmpipe the uniform reads cost the most, and more than their number (issue 42;
-- why codegen's load-once reads the tape's rows from a texture).
local function source(n, how)
  local t = {string.format("uniform vec4 uT[%d];", math.max(n, 1)), "vec4 effect(vec4 c, Image tex, vec2 tc, vec2 sc) {",
             "    vec4 s = vec4(0.0);"}
  for i = 0, n - 1 do
    local v = how == "uniform" and string.format("uT[%d]", i)
      or how == "texel" and string.format("texelFetch(tex, ivec2(%d, 0), 0)", i)
      or how == "derived" and string.format("(uT[0] * %d.5)", i)
      or string.format("vec4(%d.5, 1.25, 0.5, 2.5)", i)
    t[#t + 1] = string.format("    s = s * %s + vec4(sc, sc);", v)
  end
  t[#t + 1] = "    return s;\n}"
  return "#pragma language glsl3\n" .. table.concat(t, "\n")
end

function love.load(args)
  local counts = {}
  for _, a in ipairs(args) do if tonumber(a) then counts[#counts + 1] = tonumber(a) end end
  if #counts == 0 then counts = {70, 140, 280} end
  local canvas = love.graphics.newCanvas(16, 16)
  -- A texel for each value of the largest count (texelFetch past the edge reads 0).
  local width = math.max(unpack(counts))
  local image = love.graphics.newImage(love.image.newImageData(width, 1, "rgba32f"))
  for _, how in ipairs({"uniform", "texel", "derived", "constant"}) do
    for _, n in ipairs(counts) do
      local times = {}
      for round = 1, 3 do
        local t0 = love.timer.getTime()
        -- A comment naming the round: no cache serves a text it has seen.
        local shader = love.graphics.newShader(source(n, how) .. "\n// round " .. round)
        love.graphics.push("all")
        love.graphics.setCanvas(canvas)
        love.graphics.setShader(shader)
        love.graphics.draw(image, 0, 0, 0, 16 / width, 16)
        love.graphics.pop()
        canvas:newImageData(0, 1, 0, 0, 1, 1)
        times[round] = 1000 * (love.timer.getTime() - t0)
        shader:release()
      end
      table.sort(times)
      print(string.format("%-8s %4d values: %5.0f ms", how, n, times[2]))
    end
  end
  love.event.quit()
end
