-- What a tape interpreter's dispatch costs on the driver (issue 42):
--   SDL_VIDEODRIVER=offscreen MESA_SHADER_CACHE_DISABLE=true love tools/branch-cost CASES MODE
-- draws 640x360 pixels, each marching 96 steps through 16 spheres read from uniform
-- arrays, where every step's distance is a loop over the 16 "instructions" and each
-- instruction picks its case among CASES (1 = the sphere alone; the others are boxes
-- with some trigonometry, never taken). MODE:
--   branches  an if-else chain on the opcode, read from a uniform array by the
--             loop's counter (the same value in every pixel)
--   loops     no opcode: one loop per case over its own range of instructions, the
--             ranges of the cases not taken empty
-- Prints the compile plus first frame and the median of 5 frames. A driver that
-- skips code no pixel runs shows the same frame time for 1 and 30 cases.

local function box_case(k)
  return string.format([[{ vec3 q = abs(p - a.xyz) - vec3(%d.0 * 0.01 + a.w);
      float s = sin(q.x * %d.0) * cos(q.y * 3.0) + sin(q.z * 2.0);
      d = min(d, length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0) + 0.001 * s
                 + 0.0001 * atan(q.x, q.y)); }]], k, k)
end
local sphere_case = "{ d = min(d, length(p - a.xyz) - a.w); }"

local function scene_function(cases, mode)
  local out = {}
  if mode == "branches" then
    out[#out + 1] = "uniform int uOps[16];\nuniform vec4 uArgs[16];\n"
    out[#out + 1] = "float scene(vec3 p) {\n  float d = 1e10;\n  for (int i = 0; i < 16; i++) {\n"
    out[#out + 1] = "    int op = uOps[i]; vec4 a = uArgs[i];\n    if (op == 1) " .. sphere_case .. "\n"
    for k = 2, cases do out[#out + 1] = "    else if (op == " .. k .. ") " .. box_case(k) .. "\n" end
    out[#out + 1] = "  }\n  return d;\n}\n"
  else
    out[#out + 1] = "uniform int uStart[" .. (cases + 1) .. "];\nuniform vec4 uArgs[16];\n"
    out[#out + 1] = "float scene(vec3 p) {\n  float d = 1e10;\n"
    for k = 1, cases do
      out[#out + 1] = string.format("  for (int i = uStart[%d]; i < uStart[%d]; i++) { vec4 a = uArgs[i]; %s }\n",
                                    k - 1, k, k == 1 and sphere_case or box_case(k))
    end
    out[#out + 1] = "  return d;\n}\n"
  end
  return table.concat(out)
end

local function shader_source(cases, mode)
  return "#pragma language glsl3\n" .. scene_function(cases, mode) .. [[
vec4 effect(vec4 colour, Image tex, vec2 uv, vec2 pixel) {
  vec3 ro = vec3(0.0, 0.0, -5.0);
  vec3 rd = normalize(vec3((pixel - vec2(320.0, 180.0)) / 180.0, 1.5));
  float t = 0.0;
  for (int s = 0; s < 96; s++) {
    float d = scene(ro + rd * t);
    if (d < 0.001 || t > 20.0) break;
    t += d;
  }
  return vec4(vec3(t / 20.0), 1.0);
}
]]
end

function love.load(args)
  local cases, mode = tonumber(args[1] or "1"), args[2] or "branches"
  assert(cases and cases >= 1 and (mode == "branches" or mode == "loops"),
         "usage: love tools/branch-cost CASES branches|loops")
  local canvas = love.graphics.newCanvas(640, 360)
  local start = love.timer.getTime()
  local shader = love.graphics.newShader(shader_source(cases, mode))
  local spheres = {}
  for i = 1, 16 do spheres[i] = {math.cos(i) * 2, math.sin(i) * 1.5, i % 3, 0.4} end
  shader:send("uArgs", unpack(spheres))
  if mode == "branches" then
    local ops = {}
    for i = 1, 16 do ops[i] = 1 end
    shader:send("uOps", unpack(ops))
  else
    local starts = {0}
    for k = 1, cases do starts[k + 1] = 16 end
    shader:send("uStart", unpack(starts))
  end
  local function frame()
    love.graphics.setCanvas(canvas)
    love.graphics.setShader(shader)
    love.graphics.rectangle("fill", 0, 0, 640, 360)
    love.graphics.setShader()
    love.graphics.setCanvas()
    canvas:newImageData():release()
  end
  frame()
  local first = love.timer.getTime() - start
  local times = {}
  for i = 1, 5 do
    local t0 = love.timer.getTime()
    frame()
    times[i] = love.timer.getTime() - t0
  end
  table.sort(times)
  print(string.format("%d cases, %s: compile + first frame %.0f ms, frame %.1f ms",
                      cases, mode, first * 1000, times[3] * 1000))
  love.event.quit()
end
