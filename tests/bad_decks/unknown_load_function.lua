-- expect line 4: no load function named 'rampp'
local model = tirefe.model{}
local a = model:node{ x = 0, y = 0 }
model:load{ node = a, fx = 1, load_function = "rampp" }
