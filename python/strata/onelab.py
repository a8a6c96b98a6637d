"""The remote end of a ONELAB client: what a solver that Gmsh launches speaks on the socket.

Gmsh (the ONELAB server) starts a solver as `EXECUTABLE ... -onelab NAME ADDRESS` and waits on
ADDRESS (a Unix socket, or host:port). The solver connects, says its pid, reads and defines
parameters in Gmsh's ONELAB database, sends messages for Gmsh's console, asks Gmsh to merge
result files, and says goodbye. This is that protocol as Gmsh 4.8 speaks it (GmshSocket.h and
onelab.h, ONELAB version 1.3, in Debian's gmsh-doc under solvers/c++): a message is a header of
two native ints (type, length) and a body; a parameter travels as fields separated by NUL.

Python's gmsh module cannot do this in Gmsh 4.8: gmsh.initialize(["-onelab", NAME, ADDRESS])
connects, but gmsh.onelab.* reads and writes the client process's own database, not Gmsh's.

Parameters are dicts with the keys of ONELAB's JSON (gmsh.onelab.set): type ("number" or
"string"), name, values, and optionally label, help, visible, readOnly, attributes, choices,
min, max, step (numbers) and kind (strings).
"""

import os
import socket
import struct

VERSION = "1.3"
_SEP = "\0"
_HEADER = struct.Struct("=ii")
_CHANGED = 31  # onelab::parameter::defaultChangedValue()
_MAX = 1e200   # onelab::parameter::maxNumber()

START, STOP, INFO, WARNING, ERROR, PROGRESS = 1, 2, 10, 11, 12, 13
MERGE_FILE, PARSE_STRING, PARAMETER, PARAMETER_QUERY, PARAMETER_NOT_FOUND = 20, 21, 23, 24, 29


def _number(x):
    return repr(float(x))


def encode(p):
    """The message body of parameter p (a dict, see the module's doc)."""
    kind = p["type"]
    if kind not in ("number", "string"):
        raise ValueError(f"ONELAB parameter {p.get('name')!r}: type {kind!r} is neither number nor string")
    attributes = p.get("attributes", {})
    fields = [VERSION, kind, p["name"], p.get("label", ""), p.get("help", ""), _CHANGED,
              int(p.get("visible", True)), int(p.get("readOnly", False)), len(attributes)]
    for key, value in attributes.items():
        fields += [key, value]
    fields.append(0)  # the clients that use it: the server adds the sender
    values, choices = list(p.get("values", [])), list(p.get("choices", []))
    if kind == "number":
        labels = p.get("valueLabels", {})
        fields += [len(values)] + [_number(v) for v in values]
        fields += [_number(p.get("min", -_MAX)), _number(p.get("max", _MAX)), _number(p.get("step", 0)), -1]
        fields += [len(choices)] + [_number(c) for c in choices] + [len(labels)]
        for label, value in labels.items():
            fields += [_number(value), label]
    else:
        fields += [len(values)] + values + [p.get("kind", "generic"), len(choices)] + choices
    return "".join(str(f).replace(_SEP, " ") + _SEP for f in fields).encode()


def decode(body):
    """The parameter (a dict) in a message body."""
    tokens = iter(body.decode(errors="replace").split(_SEP))

    def counted(convert=str):
        return [convert(next(tokens)) for _ in range(int(next(tokens)))]

    version, kind = next(tokens), next(tokens)
    if version != VERSION or kind not in ("number", "string"):
        raise ValueError(f"not a ONELAB {VERSION} parameter: version {version!r}, type {kind!r}")
    p = {"type": kind, "name": next(tokens), "label": next(tokens), "help": next(tokens)}
    p["changedValue"] = int(next(tokens))
    p["visible"], p["readOnly"] = bool(int(next(tokens))), bool(int(next(tokens)))
    p["attributes"] = dict((next(tokens), next(tokens)) for _ in range(int(next(tokens))))
    p["clients"] = dict((next(tokens), int(next(tokens))) for _ in range(int(next(tokens))))
    if kind == "number":
        p["values"] = counted(float)
        p["min"], p["max"], p["step"] = float(next(tokens)), float(next(tokens)), float(next(tokens))
        p["index"] = int(next(tokens))
        p["choices"] = counted(float)
        p["valueLabels"] = {}
        for _ in range(int(next(tokens))):
            value = float(next(tokens))
            p["valueLabels"][next(tokens)] = value
    else:
        p["values"] = counted()
        p["kind"] = next(tokens)
        p["choices"] = counted()
    return p


class Client:
    """A connection to the ONELAB server (Gmsh) at address, as client name; a context manager
    that says goodbye (STOP) and closes on exit."""

    def __init__(self, name, address, timeout=300.0):
        self.name = name
        if ":" in address:
            host, port = address.rsplit(":", 1)
            self._sock = socket.create_connection((host or "localhost", int(port)), timeout=timeout)
        else:
            self._sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            self._sock.settimeout(timeout)
            self._sock.connect(address)
        self.send(START, str(os.getpid()))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self._sock is not None:
            try:
                self.send(STOP, "Goodbye!")
            finally:
                self._sock.close()
                self._sock = None

    def send(self, kind, body):
        data = body.encode() if isinstance(body, str) else body
        self._sock.sendall(_HEADER.pack(kind, len(data)) + data)

    def _receive(self):
        kind, length = _HEADER.unpack(self._read(_HEADER.size))
        return kind, self._read(length)

    def _read(self, n):
        data = b""
        while len(data) < n:
            chunk = self._sock.recv(n - len(data))
            if not chunk:
                raise ConnectionError("the ONELAB server closed the connection")
            data += chunk
        return data

    def get(self, name, kind="number"):
        """The parameter called name in the server's database (a dict), or None. A name with a
        dot that is no parameter is a Gmsh option (Mesh.MeshSizeMax): Gmsh answers its value."""
        self.send(PARAMETER_QUERY, encode({"type": kind, "name": name, "values": []}))
        reply, body = self._receive()
        if reply == PARAMETER_NOT_FOUND:
            return None
        if reply != PARAMETER:
            raise ConnectionError(f"ONELAB server: unexpected reply {reply} to a query for {name!r}")
        return decode(body)

    def values(self, name, kind="number"):
        """The values of parameter name ([] if it does not exist), as gmsh.onelab.getNumber."""
        p = self.get(name, kind)
        return p["values"] if p else []

    def set(self, p):
        """Define or update a parameter (a dict); a name with a dot sets the Gmsh option."""
        self.send(PARAMETER, encode(p))

    def info(self, text):
        self.send(INFO, text)

    def error(self, text):
        self.send(ERROR, text)

    def progress(self, text):
        self.send(PROGRESS, text)

    def merge_file(self, path):
        """Ask Gmsh to merge path (a mesh goes into a model of its own, shown with the open one)."""
        self.send(MERGE_FILE, path)

    def parse_string(self, text):
        """Ask Gmsh to parse text as .geo commands (options, e.g. `Mesh.Clip = 1;`)."""
        self.send(PARSE_STRING, text)
