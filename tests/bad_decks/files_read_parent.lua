-- expect line 3: lies outside the folders a deck may read
-- A tire property file reached with '..' out of the deck's folder and the project's.
local tire = tirefe.read_tire{ file = "../../../../../../../../etc/hostname" }
