-- Compiles the app's Fennel to Lua once, for LÖVE's start (see src/boot.lua):
--   luajit tools/build-lua.lua [--quiet]
-- writes build/lua/main.lua and build/lua/src/**/*.lua for every .fnl that changed (or
-- whose compiled file another Fennel made), and removes compiled files whose source is
-- gone. `make run`, `make test`, `make build` and `make dist` run it. A module that does
-- not compile is left out (LÖVE then compiles it at start and shows the error there);
-- the build says so and exits 1.
package.path = "./?.lua;" .. package.path .. ";lib/?.lua;/usr/share/lua/5.4/?.lua"
local fennel = require("fennel")
local boot = require("src.boot")

local quiet = arg[1] == "--quiet"

local read = boot["read-file"]

local function lines(command)
  local p = assert(io.popen(command))
  local out = {}
  for line in p:lines() do out[#out + 1] = line end
  p:close()
  return out
end

-- Written beside and renamed over: a LÖVE starting meanwhile reads the old file or the
-- new one, never half of one.
local function write_atomic(path, text)
  os.execute("mkdir -p '" .. path:match("^(.*)/") .. "'")
  local tmp = path .. ".tmp"
  local f = assert(io.open(tmp, "wb"))
  f:write(text)
  f:close()
  assert(os.rename(tmp, path))
end

local sources = lines("find src -name '*.fnl' | sort")
table.insert(sources, 1, "main.fnl")
local wanted, built, failed = {}, 0, 0
for _, path in ipairs(sources) do
  local out = boot["compiled-path"](path)
  wanted[out] = true
  local source = assert(read(path))
  if not boot.fresh(read(out), source, fennel.version) then
    local ok, lua = pcall(boot.compile, fennel, source, path)
    if ok then
      write_atomic(out, lua)
      built = built + 1
    else
      os.remove(out)
      failed = failed + 1
      io.stderr:write("build-lua: " .. tostring(lua) .. "\n")
    end
  end
end
for _, out in ipairs(lines("find build/lua -name '*.lua' 2>/dev/null")) do
  if not wanted[out] then os.remove(out) end
end
if not quiet or built > 0 or failed > 0 then
  print(("build-lua: %d of %d modules compiled to build/lua/ (the rest were current)%s")
        :format(built, #sources, failed > 0 and (", " .. failed .. " failed") or ""))
end
os.exit(failed > 0 and 1 or 0)
