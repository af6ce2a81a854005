-- expect line 3: macro 'dt'
local model = tirefe.model{}
model:dt(0.1)
