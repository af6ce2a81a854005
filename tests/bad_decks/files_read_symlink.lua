-- expect line 4: 'outside_link.csv' lies outside the folders a deck may read
-- A symbolic link in the deck's folder that leads out of it (to /etc/passwd): the path is
-- resolved before the check.
local rows = tirefe.read_csv{ file = "outside_link.csv" }
