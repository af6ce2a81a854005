-- expect line 9: '' names no file, only a folder; give a file name (e.g. 'run.h5')
-- An empty file name, or one ending in '/', names the output folder itself: it used to fail at the first flush with 'cannot rename'.
local model = tirefe.model{ title = "names" }
local a = model:node{ x = 0, y = 0 }
local b = model:node{ x = 1, y = 0 }
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = 1, rhoA = 1, rhoI = 1e-3 }
model:beam{ section = "s", nodes = { a, b } }
model:fix{ node = a }
model:output{ file = "" }
