-- The player's preview thread (see src/app/preview.fnl): draws a new scene's picture
-- with the CPU reference while a helper process compiles its shader. It takes jobs
-- from `jobs` (one wire-encoded table: id, scene, plan options, camera, sizes; or
-- "quit"), and pushes each picture to `results` as soon as it is drawn (wire:
-- {id, w, h, bytes, seconds}, or {id, error}). A job goes on only while `wanted`
-- holds its id: a newer edit, or the shader's arrival, stops it within a row.
-- Plain Lua: a LÖVE thread starts with a bare Lua state, and this puts the app's
-- modules on `require` first (src/boot.lua), as conf.lua does.
local jobs, results, wanted = ...
require("love.filesystem")
require("love.timer")
local boot = require("src.boot")
boot.install(function(path)
  if love.filesystem.getInfo(path, "file") then return (love.filesystem.read(path)) end
end)
local wire = require("src.util.wire")
local plan_mod = require("src.render.plan")
local picture = require("src.reference.picture")

-- The helper compiling the shader comes first: this thread runs at niceness 10 (the
-- background helper's), so the preview takes only what the compile leaves. Linux
-- sets a thread's own niceness by its thread id.
pcall(function()
  local ffi = require("ffi")
  local gettid = ({x64 = 186, arm64 = 178})[ffi.arch]
  if ffi.os == "Linux" and gettid then
    pcall(ffi.cdef, "long syscall(long number, ...); int setpriority(int which, int who, int prio);")
    ffi.C.setpriority(0, ffi.C.syscall(gettid), 10)   -- 0: PRIO_PROCESS
  end
end)

local function run(job)
  local id = job.id
  local function stop() return wanted:peek() ~= id end
  if stop() then return end
  local plan, err = plan_mod["scene->plan"](job.scene, job.options)
  if not plan then
    results:push((wire.encode({id = id, error = tostring(err)})))
    return
  end
  for _, size in ipairs(job.sizes) do
    local start = love.timer.getTime()
    local bytes = picture.picture(job.scene, plan, job.cam, size[1], size[2], stop)
    if not bytes then return end
    results:push((wire.encode({id = id, w = size[1], h = size[2], bytes = bytes,
                               seconds = love.timer.getTime() - start})))
  end
end

while true do
  local message = jobs:demand()
  if message == "quit" then break end
  local job, err = wire.decode(message)
  if job then
    local ok, failure = pcall(run, job)
    if not ok then results:push((wire.encode({id = job.id, error = tostring(failure)}))) end
  else
    results:push((wire.encode({id = 0, error = tostring(err)})))
  end
  -- The job's scene and plan go now: waiting for the next job allocates nothing, so
  -- the collector would not run before it.
  job, message = nil, nil
  collectgarbage()
end
