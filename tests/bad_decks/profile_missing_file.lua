-- expect line 5: no_such_road.txt
-- A road profile read from a file that does not exist.
local model = tirefe.model{}
model:node{ x = 0, y = 1 }
model:surface{ name = "road", type = "profile", file = "no_such_road.txt" }
