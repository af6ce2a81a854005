-- expect line 8: model 'second' has grown to 400001 nodes and 0 elements; the models of a deck hold at most 1000000 nodes and 1000000 elements together (2 models now)
-- Each model stays below the limit, but not both together: the limit bounds the memory of
-- the deck's models, which lies outside the Lua memory bound.
local first = tirefe.model{ title = "first" }
for i = 1, 600000 do first:node{ x = i, y = 0 } end
local second = tirefe.model{ title = "second" }
for i = 1, 1e9 do
  second:node{ x = i, y = 0 }
end
