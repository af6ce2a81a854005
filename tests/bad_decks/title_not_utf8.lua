-- expect line 3: key 'title' is not UTF-8 text (byte 4 of 8); save the deck as UTF-8
-- Text is written to result files as UTF-8: a Latin-1 title would make the file unreadable to h5py.
local model = tirefe.model{ title = "caf\xe9 run" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }

