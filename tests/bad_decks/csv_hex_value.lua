-- expect line 3: hex_value.csv:2: column 'force_N': '0x10' is not a finite number
-- Data values are decimal numbers: a hexadecimal one is refused, not read as 16.
local curve = tirefe.read_csv{ file = "hex_value.csv" }
