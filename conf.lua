-- LÖVE configuration. It also puts the app's modules on `require` (src/boot.lua's
-- install: each module's compiled Lua from build/lua/ when current, else its Fennel
-- compiled here, Fennel's compiler loaded only then) and loads main.fnl, so no main.lua
-- is needed: `love .` works right after `make run` has installed Fennel. Modules are
-- read through love.filesystem, so `love path/to/game` works from any directory.
-- (love.filesystem.read of a missing file gives nil, so no build/ is needed either.)
local boot = require("src.boot")
local function read(path)
  if love.filesystem.getInfo(path, "file") then return (love.filesystem.read(path)) end
end
boot.install(read)

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
