-- expect line 3: bad_decks
-- A CSV "file" that is a folder: it cannot be read as data.
local curve = tirefe.read_csv{ file = "../bad_decks" }
