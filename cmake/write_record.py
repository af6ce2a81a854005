"""Writes the RECORD of an installed distribution (the packaging specification's "Recording
installed projects"): every file of its packages and its .dist-info folder with its sha256
(urlsafe base64, unpadded) and size, RECORD itself without.

    write_record.py SITE_PACKAGES DIST_INFO PACKAGE...
"""
import base64
import hashlib
import os
import sys


def main():
    site, dist_info, packages = sys.argv[1], sys.argv[2], sys.argv[3:]
    rows = []
    for top in packages + [dist_info]:
        for folder, _, files in os.walk(os.path.join(site, top)):
            for name in sorted(files):
                path = os.path.join(folder, name)
                relative = os.path.relpath(path, site)
                if relative == os.path.join(dist_info, "RECORD") or name.endswith(".pyc"):
                    continue
                with open(path, "rb") as f:
                    data = f.read()
                digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
                rows.append(f"{relative},sha256={digest},{len(data)}")
    rows.append(f"{os.path.join(dist_info, 'RECORD')},,")
    with open(os.path.join(site, dist_info, "RECORD"), "w") as f:
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
