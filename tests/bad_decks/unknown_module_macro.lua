-- expect line 2: tirefe has no macro 'modle' (did you mean 'model'?)
local model = tirefe.modle{ title = "typo" }
