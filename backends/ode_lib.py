"""A thin ctypes binding of the system's ODE library: only the calls backends/ode.py makes.

The library is found at run time (ctypes.util.find_library('ode'), else Debian's
libode.so.8); importing this module raises ImportError with the install command where
it is missing, or where it was built in single precision (every struct and array below
is laid out for dReal = double: dGetConfiguration names the precision).

Layouts checked against Debian's libode-dev 0.16.2 headers (sizeof compiled there):
dContact is 248 bytes (dSurfaceParameters 120: int mode padded to 8, then 14 dReals;
dContactGeom 96 at offset 120: pos and normal are dVector3 = 4 dReals, depth, g1, g2,
side1, side2; fdir1 a dVector3 at 216); dMass is 17 dReals (mass, c[4], I[12]).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import platform

import numpy as np

INSTALL = "apt-get install libode8"
_NAMES = (ctypes.util.find_library("ode"), "libode.so.8")


# set (to anything but "" or "0"), the library is not loaded, as on a machine without it: the ode
# backend is unavailable and the tests that need it skip (.ci/run runs the tests so once)
WITHOUT = "X3DRBP_NO_ODE"


def _open() -> ctypes.CDLL:
    if os.environ.get(WITHOUT, "") not in ("", "0"):
        raise ImportError(f"{WITHOUT} is set: the ODE library is not loaded")
    for name in _NAMES:
        if not name:
            continue
        try:
            return ctypes.CDLL(name)
        except OSError:
            continue
    raise ImportError(f"the ODE library (libode) is not installed: {INSTALL}")


lib = _open()

ptr = ctypes.c_void_p
real = ctypes.c_double
reals = ctypes.POINTER(ctypes.c_double)
_i, _u = ctypes.c_int, ctypes.c_uint

# name: (restype, argtypes)
_SIGNATURES: dict[str, tuple[object, list[object]]] = {
    "dInitODE2": (_i, [_u]),
    "dAllocateODEDataForThread": (_i, [_u]),
    "dGetConfiguration": (ctypes.c_char_p, []),
    "dCheckConfiguration": (_i, [ctypes.c_char_p]),
    "dRandSetSeed": (None, [ctypes.c_ulong]),
    "dWorldCreate": (ptr, []),
    "dWorldDestroy": (None, [ptr]),
    "dWorldSetGravity": (None, [ptr, real, real, real]),
    "dWorldSetERP": (None, [ptr, real]),
    "dWorldSetCFM": (None, [ptr, real]),
    "dWorldSetQuickStepNumIterations": (None, [ptr, _i]),
    "dWorldSetContactMaxCorrectingVel": (None, [ptr, real]),
    "dWorldSetContactSurfaceLayer": (None, [ptr, real]),
    "dWorldStep": (_i, [ptr, real]),
    "dWorldQuickStep": (_i, [ptr, real]),
    "dBodyCreate": (ptr, [ptr]),
    "dBodySetPosition": (None, [ptr, real, real, real]),
    "dBodySetQuaternion": (None, [ptr, reals]),
    "dBodySetLinearVel": (None, [ptr, real, real, real]),
    "dBodySetAngularVel": (None, [ptr, real, real, real]),
    "dBodySetMass": (None, [ptr, reals]),
    "dBodySetGravityMode": (None, [ptr, _i]),
    "dBodySetKinematic": (None, [ptr]),
    "dBodySetFiniteRotationMode": (None, [ptr, _i]),
    "dBodySetFiniteRotationAxis": (None, [ptr, real, real, real]),
    "dBodyGetPosition": (reals, [ptr]),
    "dBodyGetQuaternion": (reals, [ptr]),
    "dBodyGetLinearVel": (reals, [ptr]),
    "dBodyGetAngularVel": (reals, [ptr]),
    "dBodyGetForce": (reals, [ptr]),
    "dBodyGetTorque": (reals, [ptr]),
    "dBodyGetMass": (None, [ptr, reals]),
    "dMassSetParameters": (None, [reals, real, real, real, real, real, real, real, real, real, real]),
    "dJointGroupCreate": (ptr, [_i]),
    "dJointGroupEmpty": (None, [ptr]),
    "dJointGroupDestroy": (None, [ptr]),
    "dJointAttach": (None, [ptr, ptr, ptr]),
    "dJointCreateBall": (ptr, [ptr, ptr]),
    "dJointCreateHinge": (ptr, [ptr, ptr]),
    "dJointCreateSlider": (ptr, [ptr, ptr]),
    "dJointCreateUniversal": (ptr, [ptr, ptr]),
    "dJointCreateHinge2": (ptr, [ptr, ptr]),
    "dJointCreateContact": (ptr, [ptr, ptr, ptr]),
    "dJointSetBallAnchor": (None, [ptr, real, real, real]),
    "dJointSetHingeAnchor": (None, [ptr, real, real, real]),
    "dJointSetHingeAxis": (None, [ptr, real, real, real]),
    "dJointSetHingeParam": (None, [ptr, _i, real]),
    "dJointSetSliderAxis": (None, [ptr, real, real, real]),
    "dJointSetSliderParam": (None, [ptr, _i, real]),
    "dJointGetSliderPosition": (real, [ptr]),
    "dJointGetSliderAxis": (None, [ptr, reals]),
    "dJointSetUniversalAnchor": (None, [ptr, real, real, real]),
    "dJointSetUniversalAxis1": (None, [ptr, real, real, real]),
    "dJointSetUniversalAxis2": (None, [ptr, real, real, real]),
    "dJointSetHinge2Anchor": (None, [ptr, real, real, real]),
    "dJointSetHinge2Axes": (None, [ptr, reals, reals]),
    "dJointSetHinge2Param": (None, [ptr, _i, real]),
    "dCreateBox": (ptr, [ptr, real, real, real]),
    "dCreateSphere": (ptr, [ptr, real]),
    "dCreateCylinder": (ptr, [ptr, real, real]),
    "dCreateConvex": (ptr, [ptr, reals, _u, reals, _u, ctypes.POINTER(_u)]),
    "dGeomTriMeshDataCreate": (ptr, []),
    "dGeomTriMeshDataDestroy": (None, [ptr]),
    "dGeomTriMeshDataBuildDouble": (None, [ptr, ptr, _i, _i, ptr, _i, _i]),
    "dCreateTriMesh": (ptr, [ptr, ptr, ptr, ptr, ptr]),
    "dGeomHeightfieldDataCreate": (ptr, []),
    "dGeomHeightfieldDataDestroy": (None, [ptr]),
    "dGeomHeightfieldDataBuildDouble": (None, [ptr, reals, _i, real, real, _i, _i, real, real, real, _i]),
    "dCreateHeightfield": (ptr, [ptr, ptr, _i]),
    "dGeomDestroy": (None, [ptr]),
    "dGeomSetBody": (None, [ptr, ptr]),
    "dGeomSetPosition": (None, [ptr, real, real, real]),
    "dGeomSetQuaternion": (None, [ptr, reals]),
    "dGeomSetOffsetPosition": (None, [ptr, real, real, real]),
    "dGeomSetOffsetQuaternion": (None, [ptr, reals]),
    "dGeomGetAABB": (None, [ptr, reals]),
    "dCollide": (_i, [ptr, ptr, _i, ptr, _i]),
}
for _name, (_res, _args) in _SIGNATURES.items():
    _fn = getattr(lib, _name)
    _fn.restype, _fn.argtypes = _res, _args

# ODE's message callbacks: void (*)(int errnum, const char *msg, va_list ap)
MESSAGE_FUNCTION = ctypes.CFUNCTYPE(None, ctypes.c_int, ctypes.c_char_p, ctypes.c_void_p)
for _name in ("dSetErrorHandler", "dSetDebugHandler", "dSetMessageHandler"):
    _fn = getattr(lib, _name)
    _fn.restype, _fn.argtypes = None, [MESSAGE_FUNCTION]

if not lib.dCheckConfiguration(b"ODE_double_precision"):
    raise ImportError(f"the ODE library was built without double precision ({lib.dGetConfiguration().decode()}): "
                      f"x3drbp's binding is laid out for dReal = double, as Debian's build is ({INSTALL})")
lib.dInitODE2(0)

ALLOCATE_ALL = 0xFFFFFFFF  # dAllocateMaskAll
INFINITY = float("inf")  # dInfinity in double precision

# joint parameters (common.h); add PARAM_GROUP for a joint's second axis
LO_STOP, HI_STOP, VEL, FMAX, BOUNCE, CFM, STOP_ERP, STOP_CFM, SUSPENSION_ERP, SUSPENSION_CFM = \
    0, 1, 2, 5, 7, 8, 9, 10, 11, 12
PARAM_GROUP = 0x100

# contact mode bits (contact.h)
CONTACT_MU2, CONTACT_FDIR1, CONTACT_BOUNCE, CONTACT_SOFT_ERP, CONTACT_SOFT_CFM = 0x001, 0x002, 0x004, 0x008, 0x010
CONTACT_MOTION1, CONTACT_MOTION2, CONTACT_SLIP1, CONTACT_SLIP2, CONTACT_APPROX1 = 0x020, 0x040, 0x100, 0x200, 0x7000

_VEC = (np.float64, (4,))
CONTACT = np.dtype([
    ("mode", np.int32), ("_pad", np.int32), ("mu", np.float64), ("mu2", np.float64), ("rho", np.float64),
    ("rho2", np.float64), ("rhoN", np.float64), ("bounce", np.float64), ("bounce_vel", np.float64),
    ("soft_erp", np.float64), ("soft_cfm", np.float64), ("motion1", np.float64), ("motion2", np.float64),
    ("motionN", np.float64), ("slip1", np.float64), ("slip2", np.float64),
    ("pos", _VEC), ("normal", _VEC), ("depth", np.float64), ("g1", np.uintp), ("g2", np.uintp),
    ("side1", np.int32), ("side2", np.int32), ("fdir1", _VEC)])
assert CONTACT.itemsize == 248 and CONTACT.fields["pos"][1] == 120 and CONTACT.fields["fdir1"][1] == 216
GEOM_OFFSET = CONTACT.fields["pos"][1]  # where a dContact's dContactGeom starts
MASS_REALS = 17


# x86-64's va_list is an array, so a callback receives a pointer vsnprintf takes as it is;
# elsewhere the message's format is shown unformatted
_libc = ctypes.CDLL(None) if platform.machine() in ("x86_64", "AMD64") else None
if _libc is not None:
    _libc.vsnprintf.restype = ctypes.c_int
    _libc.vsnprintf.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_char_p, ctypes.c_void_p]


def message_text(fmt: bytes | None, ap: int | None) -> str:
    """An ODE message's text: its printf format filled from its va_list (may be called once)."""
    if fmt is None:
        return ""
    if _libc is not None and ap:
        buf = ctypes.create_string_buffer(1024)
        _libc.vsnprintf(buf, len(buf), fmt, ap)
        return buf.value.decode(errors="replace")
    return fmt.decode(errors="replace")


# the callbacks installed (handlers()): kept here, alive as long as the library
_installed: list = []


def handlers(fatal, message) -> None:
    """Install ODE's error and debug handlers as fatal(kind, number, text) and its message
    handler as message(number, text). ODE calls abort() (dDebug, its assertions) or exit(1)
    (dError) once a fatal handler returns, so fatal must end the process itself; it cannot
    raise through C. The ctypes callback objects are kept alive here."""
    def wrap(kind):
        def call(num, fmt, ap):
            fatal(kind, num, message_text(fmt, ap))
        return MESSAGE_FUNCTION(call)
    error, debug = wrap("error"), wrap("internal error")
    msg = MESSAGE_FUNCTION(lambda num, fmt, ap: message(num, message_text(fmt, ap)))
    _installed[:] = [error, debug, msg]
    lib.dSetErrorHandler(error)
    lib.dSetDebugHandler(debug)
    lib.dSetMessageHandler(msg)


def version() -> str:
    """ODE has no version call: the library file's name says it (Debian: libode.so.8.0.x is ODE 0.16.x)."""
    path = getattr(lib, "_name", "libode")
    for folder in ("/usr/lib/x86_64-linux-gnu", "/usr/lib", "/usr/local/lib"):
        full = os.path.join(folder, path)
        if os.path.exists(full):
            return f"0.16 ({os.path.basename(os.path.realpath(full))}, double)"
    return f"0.16 ({path}, double)"


def array(values) -> ctypes.Array:
    """A C array of dReals holding the values (kept alive by the caller while ODE reads it)."""
    flat = np.ascontiguousarray(values, dtype=np.float64).ravel()
    return (ctypes.c_double * len(flat))(*flat)


def address(p: ctypes._Pointer) -> int:
    return ctypes.cast(p, ctypes.c_void_p).value


class Window:
    """A numpy view of ODE's own memory between the lowest and highest of some addresses,
    read and written at chosen offsets only: ODE hands out pointers into its bodies (position,
    quaternion, velocities, force accumulators), and one numpy gather over them costs
    less than four ctypes calls per body. Only the offsets given are ever touched."""

    def __init__(self, addresses: list[int], width: int):
        base = min(addresses)
        if any(a % 8 for a in addresses):
            raise ImportError("ODE returned unaligned dReal pointers")
        count = (max(addresses) - base) // 8 + width
        self.memory = np.ctypeslib.as_array((ctypes.c_double * count).from_address(base))
        self.base = base

    def index(self, addresses: list[int], width: int) -> np.ndarray:
        """(len(addresses), width) offsets into the view: each address's width dReals."""
        start = (np.asarray(addresses, dtype=np.int64) - self.base) // 8
        return start[:, None] + np.arange(width)
