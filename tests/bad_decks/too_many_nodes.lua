-- expect line 5: the models of a deck hold at most 1000000 nodes and 1000000 elements together
-- A loop that never stops adding nodes is stopped at the limit, not by the memory running out.
local model = tirefe.model{ title = "endless" }
for i = 1, 1e9 do
  model:node{ x = i, y = 0 }
end
