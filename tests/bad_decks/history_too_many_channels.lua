-- expect line 9: would be channel 10001; a result file holds at most 10000 history channels
-- Each channel is a dataset of its own: a loop that adds them without end is stopped at the
-- limit, before a hundred thousand of them cost minutes and gigabytes.
local model = tirefe.model{ title = "too many channels" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
for i = 1, 100000 do model:history{ name = "uy_" .. i, node = b, dof = "uy" } end
