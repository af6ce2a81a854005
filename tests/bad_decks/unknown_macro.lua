-- expect line 3: models have no macro 'nodee' (did you mean 'node'?)
local model = tirefe.model{}
model:nodee{ x = 0, y = 0 }
