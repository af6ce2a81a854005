-- expect line 6: setmetatable: a deck may not set a __gc finaliser (Lua runs finalisers where SIGINT and SIGTERM cannot stop them)
-- A finaliser would run with Lua's hooks off: looping there, at exit or mid-run, the deck
-- could be stopped by nothing but SIGKILL. The metatable of a table may not hold __gc
-- (one added to it later marks nothing for finalisation).
local model = tirefe.model{ title = "kept by a finaliser" }
setmetatable({}, { __gc = function() kept = model end })
