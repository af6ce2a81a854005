-- expect line 6: the deck holds 1000 models, the most at once (a model is freed once no variable holds it)
-- A model's memory lies outside the Lua memory bound: a loop that keeps every model it
-- makes is stopped at the limit. Models no variable holds are collected first.
for i = 1, 5000 do local dropped = tirefe.model{ title = "dropped " .. i } end
local kept = {}
for i = 1, 1001 do kept[i] = tirefe.model{ title = "kept " .. i } end
