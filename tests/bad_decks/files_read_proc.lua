-- expect line 3: '/proc/self/maps' lies outside the folders a deck may read
-- The process's memory map read as a road profile.
tirefe.model{}:surface{ name = "road", type = "profile", file = "/proc/self/maps" }
