-- expect line 5: node 7 does not exist
local model = tirefe.model{}
model:node{ x = 0, y = 0 }
model:node{ x = 1, y = 0 }
model:fix{ node = 7 }
