-- expect line 3: attempt to index a nil value (global 'io')
-- Decks run in a sandbox: no file or process access.
local file = io.open("/etc/passwd")
