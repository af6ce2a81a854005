-- expect line 3: no_such_data.csv
-- Measured data read from a CSV file that does not exist.
local curve = tirefe.read_csv{ file = "no_such_data.csv" }
