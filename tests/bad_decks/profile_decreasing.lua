-- expect line 5: decreasing_profile.txt', line 3: x = 1.000000 is smaller
-- A road profile whose x goes back.
local model = tirefe.model{}
model:node{ x = 0, y = 1 }
model:surface{ name = "road", type = "profile", file = "decreasing_profile.txt" }
