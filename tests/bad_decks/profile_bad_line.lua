-- expect line 5: bad_profile_line.txt', line 4: expected two numbers
-- A road profile file with a line that is not two numbers "x y".
local model = tirefe.model{}
model:node{ x = 0, y = 1 }
model:surface{ name = "road", type = "profile", file = "bad_profile_line.txt" }
