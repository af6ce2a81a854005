-- expect line 4: '}' expected
local model = tirefe.model{ title = "syntax" }
model:node{ x = 0, y = 0 }
model:node{ x = 1 y = 0 }
