-- expect line 9: surface name '..' must be a non-empty name without '/', not '.' or '..'
-- Names of surfaces, node sets, contact blocks, modal labels and history channels become paths in the result file.
local model = tirefe.model{ title = "names" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:surface{ name = "..", type = "flat" }
