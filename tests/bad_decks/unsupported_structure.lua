-- expect line 9: could not be solved
-- A beam with no supports: the tangent is singular, the step cuts run out.
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:load{ node = b, fy = 1 }
model:step_control{ max_cuts = 2 }; model:solve{ to = 1, dt = 1 }
