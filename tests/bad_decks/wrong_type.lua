-- expect line 3: key 'EI' must be a number, got string "stiff"
local model = tirefe.model{}
model:section{ name = "s", EA = 1e5, GA = 1e5, EI = "stiff" }
