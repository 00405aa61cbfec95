"""Nothing a scene names is fetched: external DTDs and entities, XInclude, Inline and
EXTERNPROTO urls, in all three encodings, go neither to the network nor outside the scene's
folder. A local HTTP server records every request (and answers with a sentinel no output
may show); the file outside the folder is a named pipe, so that opening it at all (from
Python or from libxml2) would hang the child. `x3drbp check` loads as every command does."""

from __future__ import annotations

import http.server
import os
import subprocess
import sys
import threading

import pytest

from conftest import ROOT

SENTINEL = "SENTINEL-CONTENT-7f3a"


@pytest.fixture
def server():
    """A server on 127.0.0.1 answering every GET with the sentinel; its `requests` list."""
    requests: list[str] = []

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self):
            requests.append(self.path)
            self.send_response(200)
            self.end_headers()
            self.wfile.write(SENTINEL.encode())

        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}", requests
    httpd.shutdown()


def scenes(url: str, outside: str) -> dict[str, str]:
    """File name -> text: every way a scene can name a resource, each in a file of its own."""
    rel = os.path.join("..", "outside", "pipe")
    body = ("<Scene><Inline url='\"{u}/inline.x3d\" \"{o}\" \"{r}\"'/>"
            "<ExternProtoDeclare name='P' url='\"{u}/proto.x3d#P\" \"{o}#P\" \"{r}#P\"'/>"
            "<ProtoInstance name='P'/></Scene>").format(u=url, o=outside, r=rel)
    head = "<?xml version='1.0' encoding='UTF-8'?>\n"
    return {
        "dtd_http.x3d": head + f"<!DOCTYPE X3D PUBLIC 'ISO//Web3D//DTD X3D 4.0//EN' '{url}/x3d.dtd'>\n"
                               f"<X3D profile='Full' version='4.0'>{body}</X3D>",
        "dtd_file.x3d": head + f"<!DOCTYPE X3D SYSTEM '{outside}'>\n<X3D profile='Full' version='4.0'>{body}</X3D>",
        "param_entity.x3d": head + f"<!DOCTYPE X3D [<!ENTITY % a SYSTEM '{url}/a.ent'> <!ENTITY % b SYSTEM "
                                   f"'{outside}'> %a; %b;]>\n<X3D profile='Full' version='4.0'>{body}</X3D>",
        "entity.x3d": head + f"<!DOCTYPE X3D [<!ENTITY a SYSTEM '{url}/a.ent'> <!ENTITY b SYSTEM '{outside}'>]>\n"
                             "<X3D profile='Full' version='4.0'><head><meta name='a' content='&a;&b;'/></head>"
                             f"{body}</X3D>",
        "xinclude.x3d": head + "<X3D profile='Full' version='4.0' xmlns:xi='http://www.w3.org/2001/XInclude'>"
                               f"<xi:include href='{url}/x.xml'/><xi:include href='{outside}' parse='text'/>"
                               f"{body}</X3D>",
        "stylesheet.x3d": head + f"<?xml-stylesheet type='text/xsl' href='{url}/s.xsl'?>\n"
                                 f"<X3D profile='Full' version='4.0'>{body}</X3D>",
        "urls.x3dv": "#X3D V4.0 utf8\nPROFILE Full\n"
                     f"EXTERNPROTO P [] [\"{url}/proto.x3dv#P\" \"{outside}#P\" \"{rel}#P\"]\n"
                     f"Inline {{ url [\"{url}/inline.x3dv\" \"{outside}\" \"{rel}\"] }}\nP {{}}\n",
        "urls.x3dj": '{"X3D": {"@profile": "Full", "@version": "4.0", "Scene": {"-children": ['
                     f'{{"ExternProtoDeclare": {{"@name": "P", "@url": ["{url}/p.x3dj#P", "{outside}#P", "{rel}#P"]}}}},'
                     f'{{"Inline": {{"@url": ["{url}/inline.x3dj", "{outside}", "{rel}"]}}}},'
                     '{"ProtoInstance": {"@name": "P"}}]}}}',
    }


def test_no_scene_fetches_anything(tmp_path, server):
    url, requests = server
    (tmp_path / "outside").mkdir()
    pipe = tmp_path / "outside" / "pipe"
    os.mkfifo(pipe)
    folder = tmp_path / "scenes"
    folder.mkdir()
    for name, text in scenes(url, str(pipe)).items():
        (folder / name).write_text(text)
    try:
        r = subprocess.run([sys.executable, "-m", "x3drbp", "check", str(folder)], cwd=ROOT,
                           capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("x3drbp check hung: it opened the file outside the scenes' folder")
    assert "Traceback" not in r.stderr, r.stderr
    assert all(name in r.stdout + r.stderr for name in os.listdir(folder))  # each was read
    assert SENTINEL not in r.stdout + r.stderr
    assert not requests, f"fetched {requests}"
