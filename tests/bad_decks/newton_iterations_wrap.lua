-- expect line 3: key 'max_iterations' must be an integer from 1 to 2147483647 (got number 4294967296)
local model = tirefe.model{}
model:newton{ max_iterations = 2^32 }
