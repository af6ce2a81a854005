-- expect line 3: missing required key 'EI'
local model = tirefe.model{}
model:section{ name = "s", EA = 1e5, GA = 1e5 }
