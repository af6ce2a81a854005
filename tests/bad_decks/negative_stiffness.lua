-- expect line 3: key 'EI' must be positive (got -20)
local model = tirefe.model{}
model:section{ name = "tread", EA = 3e5, GA = 8e4, EI = -20 }
