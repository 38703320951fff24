-- The uniforms of uniforms.pack (src/render/uniforms.fnl) sent to a LÖVE shader, for the
-- standalone timing programs tools/ab-run and tools/compile-run (run from the project
-- root, so `require("tools.send-uniforms")` finds this file): textures as rgba32f
-- images, nearest filtering; booleans as booleans; vectors as tables.
local comps = {float=1, int=1, bool=1, vec2=2, vec3=3, vec4=4}
return function(shader, us)
  for _, u in ipairs(us) do
    if shader:hasUniform(u.name) then
      if u.texture then
        local t = u.texture
        local data = love.image.newImageData(t.width, t.height, "rgba32f")
        local ffi = require("ffi")
        local ptr = ffi.cast("float *", data:getFFIPointer())
        for i = 0, 4 * t.width * t.height - 1 do ptr[i] = t.data[i + 1] or 0 end
        local img = love.graphics.newImage(data)
        img:setFilter("nearest", "nearest")
        shader:send(u.name, img)
      else
        local n = comps[u.type]
        local vals = {}
        if u.type == "bool" then for i, v in ipairs(u.values) do vals[i] = v ~= 0 end
        elseif n == 1 then vals = u.values
        else for i = 1, #u.values, n do local t = {} for j = 0, n - 1 do t[j + 1] = u.values[i + j] end vals[#vals + 1] = t end end
        shader:send(u.name, unpack(vals))
      end
    end
  end
end
