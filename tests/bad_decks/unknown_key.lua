-- expect line 3: unknown key 'EJ' (did you mean 'EI'?
local model = tirefe.model{}
model:section{ name = "s", EA = 1e5, GA = 1e5, EJ = 2 }
