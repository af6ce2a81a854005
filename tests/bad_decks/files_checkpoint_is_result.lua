-- expect line 12: is already the result file of model 1 ('spring') in this run; give the checkpoint
-- A checkpoint named like the model's result file would replace it on its first write.
local model = tirefe.model{ title = "spring" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:load{ node = b, fy = -1 }
model:output{ file = "spring.h5" }
model:solve{ to = 0.2, dt = 0.1 }
model:checkpoint{ file = "spring.h5", every_steps = 1 }
