-- expect line 0: is not a readable checkpoint
-- args: --restart {here}/restart_corrupt.lua
-- A restart "checkpoint" that is not one (this deck's own text).
local model = tirefe.model{}
model:node{ x = 0, y = 0 }
