-- expect line 3: load function table times must increase strictly
local model = tirefe.model{}
model:load_function{ name = "f", points = { {0, 0}, {0, 1} } }
