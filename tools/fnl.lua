-- Runs a Fennel script under LuaJIT with the project's modules on the path:
--   luajit tools/fnl.lua tools/golden.fnl [args...]
package.path = "./?.lua;" .. package.path .. ";/usr/share/lua/5.4/?.lua"
local fennel = require("fennel")
fennel.path = "./?.fnl;" .. fennel.path
-- Explicit options: see test/helper.lua. A module `make` compiled runs from build/lua/
-- while its source is unchanged (src/boot.lua): a scene worker starts without compiling.
local boot = require("src.boot")
table.insert(package.loaders, boot.searcher(boot["read-file"]))
table.insert(package.loaders, fennel.makeSearcher({allowedGlobals = false, env = false, correlate = true}))
local script = table.remove(arg, 1)
if not script then
  io.stderr:write("usage: luajit tools/fnl.lua SCRIPT.fnl [args...]\n")
  os.exit(2)
end
fennel.dofile(script, {correlate = true}, unpack(arg))
