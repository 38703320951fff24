-- The app's Fennel compiled once: `make` (tools/build-lua.lua) writes each module's
-- Lua to build/lua/PATH.lua, and the loader in conf.lua runs that instead of compiling
-- the Fennel at every start (about 1 s of CPU for the app, again for the scene worker).
--
-- A compiled file is used only if it was made from the very text now in the .fnl file:
-- its first line begins with a block comment `--[[fnl DIGEST VERSION]]`, put before the
-- compiler's first line so that line N of the Lua is still line N of the Fennel
-- (compiled with `correlate`, so errors name the Fennel line). An edited source, or no
-- build at all, compiles the source as before. The build also recompiles what another
-- Fennel version made; the app does not look at the version, which would mean loading
-- Fennel (its compiler is needed only for scene files and stale modules).
-- Plain Lua, so that conf.lua and the build script need nothing loaded first.

local bit = require("bit")

-- The options every module is compiled with, here and in conf.lua's fallback.
local options = {correlate = true}

--- FNV-1a (32 bits) of `text`, as 8 hex digits. Not a defence against anyone: it only
--- tells an edited source from the one a build compiled.
local function digest(text)
  local h = 2166136261
  local bxor, band, byte = bit.bxor, bit.band, string.byte
  for i = 1, #text do
    -- h * 16777619 mod 2^32, in two halves so that no product leaves a double's
    -- 53 exact bits: 16777619 = 2^24 + 403.
    h = bxor(h, byte(text, i))
    h = band(h * 403 + bit.lshift(band(h, 0xff), 24), 0xffffffff)
  end
  return bit.tohex(h)
end

--- Where the compiled Lua of the Fennel file `path` (relative to the game) lives.
local function compiled_path(path)
  return "build/lua/" .. path:gsub("%.fnl$", ".lua")
end

--- The key a compiled file of `source` carries: its digest, then the Fennel version
--- (`version` nil: the key's start, which any version matches).
local function key(source, version)
  local start = "--[[fnl " .. digest(source) .. " "
  if version then return start .. version .. "]]" end
  return start
end

--- The Lua of `source` (Fennel text of `path`) with its key before the first line.
local function compile(fennel, source, path)
  local lua = fennel.compileString(source, {filename = path, correlate = options.correlate})
  return key(source, fennel.version) .. lua
end

--- The compiled text if `compiled` (a file's text, or nil) was made from `source` (by
--- Fennel `version`, if given); nil otherwise.
local function fresh(compiled, source, version)
  if compiled then
    local k = key(source, version)
    if compiled:sub(1, #k) == k then return compiled end
  end
  return nil
end

--- A package searcher that runs a module's compiled Lua when it is fresh, and leaves
--- the module to the next searcher (Fennel's) otherwise. `read` gives a file's text
--- by its path relative to the game, or nil.
local function searcher(read)
  return function(name)
    local path = name:gsub("%.", "/") .. ".fnl"
    local source = read(path)
    local lua = source and fresh(read(compiled_path(path)), source)
    if lua then
      return function(...) return assert(loadstring(lua, "@" .. path))(...) end
    end
  end
end

--- `read` for plain LuaJIT (tools/fnl.lua, the tests): files relative to the
--- working directory.
local function read_file(path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local text = f:read("*a")
  f:close()
  return text
end

--- Where Fennel's compiler is looked for: the project's lib/ (make deps), then Debian's.
local fennel_path = ";lib/?.lua;/usr/share/lua/5.4/?.lua;/usr/share/lua/5.3/?.lua"

--- Put the app's modules on `require` in this Lua state (conf.lua's, a LÖVE thread's):
--- a module runs from its compiled Lua in build/lua/ when that was compiled from the
--- source as it is now (`searcher`), else its Fennel is compiled here, the compiler
--- loaded only then. `read` gives a file's text by its path relative to the game, or nil.
local function install(read)
  package.path = package.path .. fennel_path
  local fennel
  local function compiler()
    if not fennel then
      local ok, f = pcall(require, "fennel")
      if not ok then
        error("Fennel is not installed (looked for fennel.lua in lib/ and /usr/share/lua/5.4/).\n"
              .. "Run `make run` once: it installs what is missing.")
      end
      fennel = f
    end
    return fennel
  end
  table.insert(package.loaders, 2, searcher(read))
  table.insert(package.loaders, 3, function(name)
    local path = name:gsub("%.", "/") .. ".fnl"
    local source = read(path)
    if source then
      return function(...)
        local lua = compiler().compileString(source, {filename = path, correlate = options.correlate})
        return assert(loadstring(lua, "@" .. path))(...)
      end
    end
  end)
end

return {digest = digest, searcher = searcher, install = install, ["read-file"] = read_file, ["compiled-path"] = compiled_path, key = key,
        compile = compile, fresh = fresh, options = options}
