-- expect line 4: '../escape.tir' lies outside the output folder
-- A file written above the output folder with '..'.
local tire = require("tires.145SR12")
tirefe.write_tire{ file = "../escape.tir", parameters = tire }
