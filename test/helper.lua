-- Test bootstrap: puts Fennel on the path, teaches busted to load *_spec.fnl files,
-- and turns accidental global writes into errors.
package.path = "./?.lua;./?/init.lua;" .. package.path .. ";/usr/share/lua/5.4/?.lua"
local fennel = require("fennel")
fennel.path = "./?.fnl;./?/init.fnl;" .. fennel.path
-- An explicit searcher: fennel.searcher copies the options of the compile in progress,
-- and a failed sandboxed scene compile would otherwise leak its env and allowed globals
-- into the next module loaded. env false (not _G): the modules run on the real globals,
-- as in LÖVE (conf.lua), not through Fennel's wrapper, whose __index unmangles every
-- global name it is asked for (12% of the CPU time of grid_spec and reference_spec).
table.insert(package.loaders or package.searchers,
             fennel.makeSearcher({allowedGlobals = false, env = false, correlate = true}))
-- Compile with line correlation so tracebacks point at the right Fennel lines.
fennel["macro-path"] = "./?.fnl;" .. fennel["macro-path"]

package.preload["busted.modules.files.fennel"] = function()
  local path = require("pl.path")
  local loader = {}
  function loader.match(_, filename)
    return path.extension(filename) == ".fnl"
  end
  function loader.load(busted, filename)
    local f = assert(io.open(filename, "rb"))
    local source = f:read("*a")
    f:close()
    local ok, chunk = pcall(function()
      local lua = fennel.compileString(source, {filename = filename, correlate = true})
      return assert(loadstring(lua, "@" .. filename))
    end)
    if not ok then
      busted.publish({"error", "file"}, {descriptor = "file", name = filename}, nil, chunk, {})
      return nil
    end
    return chunk, function(_, info) return info end, function(_, msg) return msg end
  end
  return loader
end

setmetatable(_G, {
  __newindex = function(_, name)
    error("test wrote to global '" .. tostring(name) .. "'", 2)
  end,
})
