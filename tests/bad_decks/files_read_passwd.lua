-- expect line 4: '/etc/passwd' lies outside the folders a deck may read
-- A system file read as CSV data: refused before it is opened, so no line of it can
-- show in the message.
local rows = tirefe.read_csv{ file = "/etc/passwd" }
