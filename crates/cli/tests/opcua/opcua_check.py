"""A real OPC UA client (asyncua from PyPI) against `automat run` serving
the program of crates/cli/tests/opcua.rs: browse, read with types, the
anonymous session read-only, an untrusted client certificate refused,
then (after the test trusted it) a wrong password refused, a viewer that
reads but cannot write, an operator on Basic256Sha256 Sign and on
SignAndEncrypt writing through the session's rules (a CONSTANT refused, a
wrong type refused, an array written whole) and a subscription sampled
at the scan. Prints one line per check and `N passed, M failed`.

usage: opcua_check.py URL CERT KEY PHASE   (PHASE: untrusted | trusted)
"""
import asyncio
import sys

from asyncua import Client, ua
from asyncua.crypto.security_policies import SecurityPolicyBasic256Sha256

URL, CERT, KEY, PHASE = sys.argv[1:5]
passed = failed = 0


def check(name, got, want):
    global passed, failed
    if got == want:
        passed += 1
        print(f"ok   {name}")
    else:
        failed += 1
        print(f"FAIL {name}: got {got!r}, want {want!r}")


async def secure(user, password, mode):
    c = Client(URL, timeout=10)
    c.application_uri = "urn:automat:test"
    await c.set_security(SecurityPolicyBasic256Sha256, CERT, KEY, mode=mode)
    c.set_user(user)
    c.set_password(password)
    return c


async def refused(coro):
    try:
        await coro
        return "accepted"
    except Exception as e:  # asyncua raises a status-code exception
        return type(e).__name__


def node(c, path):
    return c.get_node(f"ns=1;s={path}")


async def write(c, path, value, vt):
    await node(c, path).write_value(ua.DataValue(ua.Variant(value, vt)))


class Changes:
    def __init__(self):
        self.values = []

    def datachange_notification(self, node, val, data):
        self.values.append(val)


async def anonymous():
    async with Client(URL, timeout=10) as c:
        names = [(await n.read_browse_name()).Name for n in await c.nodes.objects.get_children()]
        check("Objects has the program folder Main and Globals", ("Main" in names, "Globals" in names), (True, True))
        kids = {(await n.read_browse_name()).Name: n for n in await node(c, "Main").get_children()}
        check(
            "Main's children (no compiler-generated names)",
            sorted(kids),
            ["LIMIT", "cmd", "lamp", "level", "levels", "name", "sensor", "speed", "t", "wait"],
        )
        check("a TON instance is an object", await kids["t"].read_node_class(), ua.NodeClass.Object)
        t_kids = sorted([(await n.read_browse_name()).Name for n in await kids["t"].get_children()])
        check("Main.t's members", t_kids, ["ET", "IN", "PT", "Q"])
        check("NodeId ns=1;s=<path>", kids["level"].nodeid.to_string(), "ns=1;s=Main.level")
        for path, value, vt in [
            ("Main.level", 7, ua.VariantType.Int16),
            ("Main.speed", 1.5, ua.VariantType.Float),
            ("Main.levels", [10, 20, 30], ua.VariantType.Int32),
            ("Main.name", "tank", ua.VariantType.String),
            ("Main.wait", 1500.0, ua.VariantType.Double),
            ("Main.t.Q", False, ua.VariantType.Boolean),
            ("Main.LIMIT", 99, ua.VariantType.Int16),
            ("total", 0, ua.VariantType.UInt32),
        ]:
            dv = await node(c, path).read_data_value()
            check(f"read {path}", (dv.Value.Value, dv.Value.VariantType), (value, vt))
        check("data type of Main.wait is Duration", (await node(c, "Main.wait").read_data_type()).to_string(), "i=290")
        check("Main.levels is an array of 3", await node(c, "Main.levels").read_array_dimensions(), [3])
        check(
            "anonymous cannot write",
            await refused(write(c, "Main.cmd", 20, ua.VariantType.Int16)),
            "BadUserAccessDenied",
        )


async def trusted():
    c = await secure("op", "wrong-password", ua.MessageSecurityMode.SignAndEncrypt)
    check("a wrong password is refused", await refused(c.connect()), "BadIdentityTokenRejected")
    c = await secure("nobody", "secret-op1", ua.MessageSecurityMode.SignAndEncrypt)
    check("an unknown user is refused", await refused(c.connect()), "BadIdentityTokenRejected")
    v = await secure("view", "secret-view2", ua.MessageSecurityMode.Sign)
    async with v:
        check("viewer on Basic256Sha256 Sign reads", await node(v, "Main.level").read_value(), 7)
        check(
            "viewer cannot write",
            await refused(write(v, "Main.cmd", 20, ua.VariantType.Int16)),
            "BadUserAccessDenied",
        )
    c = await secure("op", "secret-op1", ua.MessageSecurityMode.SignAndEncrypt)
    async with c:
        changes = Changes()
        sub = await c.create_subscription(20, changes)
        await sub.subscribe_data_change(node(c, "Main.level"), sampling_interval=10)
        await asyncio.sleep(0.3)
        await write(c, "Main.sensor", 5, ua.VariantType.Int16)
        await write(c, "Main.cmd", 20, ua.VariantType.Int16)
        await asyncio.sleep(0.4)
        check("operator writes: sensor 5 -> level 12", await node(c, "Main.level").read_value(), 12)
        check("... and cmd 20 -> lamp", await node(c, "Main.lamp").read_value(), True)
        check("the subscription saw 7 then 12", changes.values[-2:], [7, 12])
        await write(c, "Main.sensor", 6, ua.VariantType.Int16)
        await asyncio.sleep(0.4)
        check("... then 13", changes.values[-1], 13)
        await write(c, "Main.levels", [1, 2, 3], ua.VariantType.Int32)
        await write(c, "Main.speed", 2.5, ua.VariantType.Float)
        await write(c, "Main.name", "it's", ua.VariantType.String)
        await asyncio.sleep(0.2)
        check("an array written whole", await node(c, "Main.levels").read_value(), [1, 2, 3])
        check("a REAL written", await node(c, "Main.speed").read_value(), 2.5)
        check("a STRING written", await node(c, "Main.name").read_value(), "it's")
        check(
            "a CONSTANT is not writable",
            await refused(write(c, "Main.LIMIT", 1, ua.VariantType.Int16)),
            "BadUserAccessDenied",
        )
        check(
            "a value of another type is refused",
            await refused(write(c, "Main.cmd", 1, ua.VariantType.Int32)),
            "BadTypeMismatch",
        )
        await sub.delete()


async def untrusted():
    c = await secure("op", "secret-op1", ua.MessageSecurityMode.SignAndEncrypt)
    check("an untrusted client certificate is refused", await refused(c.connect()), "BadCertificateUntrusted")


if PHASE == "untrusted":
    asyncio.run(anonymous())
    asyncio.run(untrusted())
else:
    asyncio.run(trusted())
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
