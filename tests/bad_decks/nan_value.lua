-- expect line 3: key 'x' is not a finite number
local model = tirefe.model{}
model:node{ x = 0/0, y = 0 }
