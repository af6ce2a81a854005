-- expect line 4: 'curve_points' = 1000000000 is more than a plot needs (at most 10000)
-- A fit asking for its model on an absurd grid: refused before any model evaluation.
local data = { 1, 2, 3 }
tirefe.fit{ parameters = { { name = "k", initial = 1, lower = 0.1, upper = 10 } }, data = data,
            model = function(p) return { p.k, 2 * p.k, 3 * p.k } end, curve_points = 1000000000 }
