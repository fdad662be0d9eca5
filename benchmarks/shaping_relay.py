"""A slow link on loopback: a TCP relay that limits the rate and delays the bytes, both ways.

``benchmarks/bench_link.py`` puts it between Chromium and JupyterLab, so that every
connection (the page's HTTP requests and the kernel's WebSocket) crosses a link like a
student's on Binder.  Each direction of the link is shared by every connection through it:

- a **token bucket** lets bytes pass at ``rate`` bytes/s, with bursts of at most ``burst``
  bytes when the link was idle; the bytes of all connections wait their turn in one queue,
  as on a real link;
- then every byte is held back for the **one-way delay** (half the round trip) before it is
  written on, in the order it came: nothing is reordered.

Run by hand, it puts a slow link in front of any local server (a lab started with
``make lab`` on port 8888, say) for a look in a real browser::

    .venv/bin/python -m benchmarks.shaping_relay --target 8888 --port 8890 --mbit 10 --rtt-ms 60
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import threading

PIECE = 16 * 1024  # bytes: a chunk read from a socket crosses the bucket in pieces this size
BURST = 16 * 1024  # bytes the bucket holds: what an idle link lets through at once
READ_SIZE = 64 * 1024


class Direction:
    """One direction of the link: a token bucket shared by every connection, then a delay.

    Parameters
    ----------
    rate : float
        Bytes per second the link carries.
    delay : float
        One-way delay, s.
    burst : int
        Bytes the bucket holds when full.
    """

    def __init__(self, rate: float, delay: float, burst: int = BURST):
        if not rate > 0:
            raise ValueError(f"rate must be positive, got {rate!r}")
        if not delay >= 0:
            raise ValueError(f"delay must be >= 0, got {delay!r}")
        self.rate = rate
        self.delay = delay
        self.burst = burst
        self.bytes = 0  # carried so far
        self._tokens = float(burst)
        self._stamp: float | None = None
        self._lock: asyncio.Lock | None = None

    async def carry(self, n: int) -> float:
        """Wait until ``n`` bytes have passed the bucket; returns the loop time they reach the far end."""
        loop = asyncio.get_running_loop()
        if self._lock is None:
            self._lock = asyncio.Lock()
            self._stamp = loop.time()
        async with self._lock:  # one queue for every connection: first come, first through
            now = loop.time()
            self._tokens = min(self.burst, self._tokens + (now - self._stamp) * self.rate)
            self._stamp = now
            self._tokens -= n
            if self._tokens < 0:  # the bytes are on the wire until the debt is paid
                await asyncio.sleep(-self._tokens / self.rate)
            self.bytes += n
            return loop.time() + self.delay


async def _pipe(reader: asyncio.StreamReader, writer: asyncio.StreamWriter, direction: Direction) -> None:
    """Copy ``reader`` to ``writer`` through ``direction``, in order; half-close ``writer`` at the end."""
    loop = asyncio.get_running_loop()
    queue: asyncio.Queue = asyncio.Queue()

    async def deliver() -> None:
        while (item := await queue.get()) is not None:
            arrival, data = item
            await asyncio.sleep(max(0.0, arrival - loop.time()))
            writer.write(data)
            await writer.drain()
        if writer.can_write_eof():
            writer.write_eof()

    delivering = asyncio.create_task(deliver())
    try:
        while data := await reader.read(READ_SIZE):
            for start in range(0, len(data), PIECE):
                piece = data[start : start + PIECE]
                queue.put_nowait((await direction.carry(len(piece)), piece))
    finally:
        queue.put_nowait(None)
        await delivering


class ShapingRelay:
    """Listens on 127.0.0.1 and relays every connection to ``target_port`` over a slow link.

    The relay runs its own event loop in a background thread, so a synchronous program
    (Playwright's sync API, ``urllib``) can use it.

    Parameters
    ----------
    target_port : int
        The local server's port.
    mbit : float
        Rate of each direction, Mbit/s (10**6 bits).
    rtt_ms : float
        Round trip, ms; each direction delays by half of it.
    port : int
        Port to listen on; 0 picks a free one (see :attr:`port` once started).

    Attributes
    ----------
    down, up : Direction
        Server to browser, browser to server; ``.bytes`` counts what each carried.
    """

    def __init__(self, target_port: int, mbit: float = 10.0, rtt_ms: float = 60.0, port: int = 0):
        if not mbit > 0:
            raise ValueError(f"mbit must be positive, got {mbit!r}")
        if not rtt_ms >= 0:
            raise ValueError(f"rtt_ms must be >= 0, got {rtt_ms!r}")
        self.target_port = target_port
        self.mbit = mbit
        self.rtt_ms = rtt_ms
        self.port = port
        self.down = Direction(mbit * 1e6 / 8, rtt_ms / 2000)
        self.up = Direction(mbit * 1e6 / 8, rtt_ms / 2000)
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name="shaping-relay", daemon=True)
        self._server: asyncio.Server | None = None
        self._connections: set[asyncio.Task] = set()

    async def _relay(self, client_reader: asyncio.StreamReader, client_writer: asyncio.StreamWriter) -> None:
        """One connection: open the same to the target, then carry both directions until both end."""
        task = asyncio.current_task()
        self._connections.add(task)  # the event loop holds tasks only weakly: keep this one until it ends
        try:
            await self._carry(client_reader, client_writer)
        except asyncio.CancelledError:
            pass  # the relay stops (ending here, not cancelled, keeps asyncio's stream callback quiet)
        finally:
            self._connections.discard(task)

    async def _carry(self, client_reader: asyncio.StreamReader, client_writer: asyncio.StreamWriter) -> None:
        try:
            server_reader, server_writer = await asyncio.open_connection("127.0.0.1", self.target_port)
        except OSError:
            client_writer.close()
            return
        try:
            await asyncio.gather(
                _pipe(client_reader, server_writer, self.up),
                _pipe(server_reader, client_writer, self.down),
            )
        except (ConnectionError, OSError):
            pass  # one side went away: close both
        finally:
            for writer in (client_writer, server_writer):
                writer.close()
                with contextlib.suppress(ConnectionError, OSError):
                    await writer.wait_closed()

    async def _listen(self) -> int:
        self._server = await asyncio.start_server(self._relay, "127.0.0.1", self.port)
        return self._server.sockets[0].getsockname()[1]

    def start(self) -> ShapingRelay:
        """Start listening; returns the relay, with :attr:`port` set."""
        self._thread.start()
        self.port = asyncio.run_coroutine_threadsafe(self._listen(), self._loop).result()
        return self

    def stop(self) -> None:
        """Stop listening, drop every connection and end the thread."""

        async def close() -> None:
            self._server.close()
            # A cancelled connection still closes its sockets, which may wake other tasks: repeat.
            while tasks := [t for t in asyncio.all_tasks() if t is not asyncio.current_task()]:
                for task in tasks:
                    task.cancel()
                await asyncio.gather(*tasks, return_exceptions=True)

        if self._server is not None:
            asyncio.run_coroutine_threadsafe(close(), self._loop).result()
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join()
        self._loop.close()

    def __enter__(self) -> ShapingRelay:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description="Relay a local server's port over a slow link.")
    parser.add_argument("--target", type=int, required=True, help="the local server's port")
    parser.add_argument("--port", type=int, default=0, help="port to listen on (default: a free one)")
    parser.add_argument("--mbit", type=float, default=10.0, help="rate each way, Mbit/s (default 10)")
    parser.add_argument("--rtt-ms", type=float, default=60.0, help="round trip, ms (default 60)")
    args = parser.parse_args(argv)
    relay = ShapingRelay(args.target, args.mbit, args.rtt_ms, args.port).start()
    print(f"http://127.0.0.1:{relay.port}/ -> 127.0.0.1:{args.target} at {args.mbit:g} Mbit/s, {args.rtt_ms:g} ms RTT")
    try:
        threading.Event().wait()
    except KeyboardInterrupt:
        relay.stop()


if __name__ == "__main__":
    main()
