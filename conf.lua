-- LÖVE configuration. It also puts Fennel on the module path and loads main.fnl, so
-- no main.lua is needed: `love .` works right after `make run` has installed Fennel.
-- (love.filesystem.read of a missing file gives nil, so no build/ is needed either.)
package.path = package.path .. ";lib/?.lua;/usr/share/lua/5.4/?.lua;/usr/share/lua/5.3/?.lua"
local boot = require("src.boot")

-- Fennel's compiler is loaded only when a module must be compiled here (no build, or
-- its source edited since) or a scene file is read: a start from a build needs none.
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

-- Modules are read through love.filesystem, so `love path/to/game` works from any
-- directory. A module runs from its compiled Lua in build/lua/ (made by `make`, see
-- src/boot.lua) when that was compiled from the source as it is now; otherwise it is
-- compiled here. Either way line numbers in errors are the Fennel source's.
local function read(path)
  if love.filesystem.getInfo(path, "file") then return (love.filesystem.read(path)) end
end
table.insert(package.loaders, 2, boot.searcher(read))
table.insert(package.loaders, 3, function(name)
  local path = name:gsub("%.", "/") .. ".fnl"
  local source = read(path)
  if source then
    return function(...)
      local lua = compiler().compileString(source, {filename = path,
                                                    correlate = boot.options.correlate})
      return assert(loadstring(lua, "@" .. path))(...)
    end
  end
end)

-- Command-line modes that only print need no window.
local function has_arg(flag)
  for _, a in ipairs(arg or {}) do
    if a == flag then return true end
  end
  return false
end

function love.conf(t)
  t.identity = "fennel-raymarcher"
  t.version = "11.4"
  t.window.title = "Fennel raymarcher"
  t.window.width = 1280
  t.window.height = 720
  t.window.resizable = true
  t.window.minwidth = 64
  t.window.minheight = 48
  t.window.vsync = 0
  t.modules.audio = false   -- no sound device on CI
  t.modules.sound = false
  t.modules.physics = false
  t.modules.video = false
  if has_arg("--print-shader") or has_arg("--kinds") or has_arg("--tree")
     or has_arg("--help") or has_arg("--help-dev") or has_arg("-h") or has_arg("--export-shader")
     or (has_arg("--probe") and not has_arg("--gpu")) or has_arg("--scene-worker") then
    t.window = nil
    t.modules.window = false
    t.modules.graphics = false
  end
  -- The scene worker needs only the file system (its modules are read through it).
  if has_arg("--scene-worker") then
    for name in pairs(t.modules) do t.modules[name] = (name == "filesystem") end
  end
end

-- The player's compile helper loads only what it needs (see src/app/warm-helper.fnl).
if has_arg("--warm-shader") or has_arg("--warm-server") then
  require("src.app.warm-helper")["install!"]()
-- The scene worker (src/scene/worker-main.fnl) loads the scene loader and nothing else.
elseif has_arg("--scene-worker") then
  require("src.scene.worker-main")["run-love!"]()
else
  require("main")
end
