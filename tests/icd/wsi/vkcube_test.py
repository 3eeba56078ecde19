#!/usr/bin/python3
"""Debian's vkcube, a windowed Vulkan program, on tilevk alone and on lavapipe alone, under Xvfb (the script starts
its own X server with xvfb-run, so no display is needed): `vkcube --c 100` must exit 0 on every run, and the window
as the X server shows it when vkcube destroys it (captured with xwd by capture_window.so, preloaded) must be the same
bytes on tilevk as on lavapipe, except where lavapipe's own two runs differ from each other (none so far: the test
prints how many). tilevk runs with its three present modes and with MIT-SHM off (the PutImage path); FIFO must be
paced (100 frames at 60 Hz take at least 1.5 s). One tilevk run has the validation layer on (vkcube --validate):
it must print no message. Then, if weston is installed, vkcube-wayland on weston's headless backend: exit 0 on both
drivers, and tilevk's frames reach the compositor (wl_surface.commit with a wl_shm buffer, counted in the protocol
trace of WAYLAND_DEBUG=client).

Usage: vkcube_test.py CAPTURE_SO TILEVK_JSON LAVAPIPE_JSON VKCUBE VKCUBE_WAYLAND XVFB_RUN XWD WESTON
"""
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time

FRAMES = 100


def read_xwd(path):
    """(width, height, rows of B,G,R bytes) of a 32-bit ZPixmap XWD file (xwd's own format: a big-endian header)."""
    with open(path, 'rb') as f:
        data = f.read()
    h = struct.unpack('>25I', data[:100])
    header_size, width, height, byte_order, bits_per_pixel, bytes_per_line, ncolors = \
        h[0], h[4], h[5], h[7], h[11], h[12], h[19]
    if bits_per_pixel != 32 or byte_order != 0:
        raise ValueError(f'{path}: {bits_per_pixel} bits per pixel, byte order {byte_order}: not 32-bit LSBFirst')
    pixels = data[header_size + 12 * ncolors:]
    return width, height, [bytes(pixels[y * bytes_per_line + 4 * x + c] for x in range(width) for c in range(3))
                           for y in range(height)]


def differing(a, b):
    """The set of (x, y) whose blue, green, red differ."""
    if a[:2] != b[:2]:
        raise ValueError(f'sizes differ: {a[:2]} vs {b[:2]}')
    out = set()
    for y, (ra, rb) in enumerate(zip(a[2], b[2])):
        if ra != rb:
            out.update((i // 3, y) for i in range(len(ra)) if ra[i] != rb[i])
    return out


def run_vkcube(args, icd, env_extra, capture, work, timeout=180):
    env = dict(os.environ)
    env.update({'VK_ICD_FILENAMES': icd, 'VK_DRIVER_FILES': icd, 'LD_PRELOAD': args['capture_so'],
                'TILEVK_CAPTURE_XWD': capture})
    env.pop('TILEVK_CAPTURE_DONE', None)
    env.update(env_extra['env'])
    start = time.monotonic()
    p = subprocess.run([args['vkcube'], '--c', str(FRAMES)] + env_extra['args'], env=env, cwd=work,
                       capture_output=True, text=True, timeout=timeout)
    return p.returncode, time.monotonic() - start, p.stdout + p.stderr


def inner(args):
    failures = []
    work = tempfile.mkdtemp(prefix='tilevk-vkcube-')
    tvk, lvp = args['tilevk'], args['lavapipe']
    runs = [  # name, manifest, environment, vkcube arguments, paced
        ('lavapipe', lvp, {}, [], False),
        ('lavapipe again', lvp, {}, [], False),
        ('tilevk FIFO', tvk, {}, [], True),
        ('tilevk FIFO, PutImage (TILEVK_WSI_SHM=0)', tvk, {'TILEVK_WSI_SHM': '0'}, [], True),
        ('tilevk MAILBOX', tvk, {}, ['--present_mode', '1'], False),
        ('tilevk IMMEDIATE', tvk, {}, ['--present_mode', '0'], False),
        ('tilevk FIFO, validation layer', tvk, {}, ['--validate', '--suppress_popups'], True),
    ]
    captures = {}
    for name, icd, env, extra, paced in runs:
        capture = os.path.join(work, f'{len(captures)}.xwd')
        rc, seconds, out = run_vkcube(args, icd, {'env': env, 'args': extra}, capture, work)
        lines = [l for l in out.splitlines() if l.strip() and not l.startswith('Selected GPU')]
        print(f'{name}: exit {rc}, {seconds:.2f} s, {len(lines)} other output line(s)')
        for l in lines[:10]:
            print('   ', l)
        if rc != 0:
            failures.append(f'{name}: vkcube exited {rc}')
        if icd == tvk and lines:
            failures.append(f'{name}: vkcube or tilevk printed {len(lines)} line(s) (messages, validation)')
        if paced and seconds < 1.5:
            failures.append(f'{name}: {FRAMES} FIFO frames in {seconds:.2f} s: not paced to 60 Hz')
        if not os.path.exists(capture):
            failures.append(f'{name}: no capture of the window')
            continue
        captures[name] = read_xwd(capture)
    if 'lavapipe' in captures and 'lavapipe again' in captures:
        ref = captures['lavapipe']
        unstable = differing(ref, captures['lavapipe again'])
        print(f'lavapipe run to run: {len(unstable)} pixel(s) differ ({ref[0]}x{ref[1]} window)')
        for name, cap in captures.items():
            if name.startswith('tilevk'):
                d = differing(ref, cap)
                outside = d - unstable
                print(f'{name} vs lavapipe: {len(d)} pixel(s) differ, {len(outside)} outside lavapipe\'s own')
                if outside:
                    failures.append(f'{name}: {len(outside)} pixel(s) differ from lavapipe, e.g. {sorted(outside)[:5]}')
    else:
        failures.append('no lavapipe capture to compare with')
    shutil.rmtree(work, ignore_errors=True)
    return failures


def wayland(args):
    """vkcube-wayland on weston's headless backend (skipped, and said so, without weston)."""
    if not os.path.exists(args['weston']) or not os.path.exists(args['vkcube_wayland']):
        print('Wayland: SKIPPED (weston or vkcube-wayland is not installed)')
        return []
    failures = []
    runtime = tempfile.mkdtemp(prefix='tilevk-wl-')
    os.chmod(runtime, 0o700)
    socket = 'tilevk-test-0'
    env = dict(os.environ, XDG_RUNTIME_DIR=runtime)
    env.pop('DISPLAY', None)
    weston = subprocess.Popen([args['weston'], '--backend=headless-backend.so', f'--socket={socket}',
                               '--idle-time=0', '--width=640', '--height=480'], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        for _ in range(100):
            if os.path.exists(os.path.join(runtime, socket)):
                break
            time.sleep(0.1)
        else:
            return ['Wayland: weston did not open its socket']
        env['WAYLAND_DISPLAY'] = socket
        for name, icd in (('lavapipe', args['lavapipe']), ('tilevk', args['tilevk'])):
            e = dict(env, VK_ICD_FILENAMES=icd, VK_DRIVER_FILES=icd, WAYLAND_DEBUG='client')
            p = subprocess.run([args['vkcube_wayland'], '--c', '30'], env=e, capture_output=True, text=True,
                               timeout=120)
            trace = p.stderr.splitlines()
            commits = sum(1 for l in trace if '-> wl_surface@' in l and '.commit()' in l)
            attaches = sum(1 for l in trace if '-> wl_surface@' in l and '.attach(wl_buffer@' in l)
            errors = [l for l in trace if 'tilevk:' in l or 'error' in l.lower()]
            print(f'Wayland {name}: exit {p.returncode}, {attaches} buffer attaches, {commits} commits')
            for l in errors[:5]:
                print('   ', l)
            if p.returncode != 0:
                failures.append(f'Wayland {name}: vkcube-wayland exited {p.returncode}')
            if name == 'tilevk' and (attaches != 30 or errors):
                failures.append(f'Wayland tilevk: {attaches} frames attached (30 presented), {len(errors)} errors')
    finally:
        os.killpg(weston.pid, signal.SIGTERM)
        weston.wait(timeout=30)
        shutil.rmtree(runtime, ignore_errors=True)
    return failures


def main():
    names = ['capture_so', 'tilevk', 'lavapipe', 'vkcube', 'vkcube_wayland', 'xvfb_run', 'xwd', 'weston']
    if len(sys.argv) >= 2 and sys.argv[1] == '--inner':
        args = dict(zip(names, sys.argv[2:]))
        failures = inner(args)
    else:
        args = dict(zip(names, sys.argv[1:]))
        if len(args) != len(names):
            print(__doc__)
            return 2
        # The X part under its own X server; -noreset keeps it up between the runs' connections.
        os.environ['PATH'] = os.path.dirname(args['xwd']) + os.pathsep + os.environ.get('PATH', '')
        # -n 140: the first display number tried, apart from icd_wsi_x11's (meson starts both at once).
        p = subprocess.run([args['xvfb_run'], '-a', '-n', '140', '-s', '-screen 0 1024x768x24 -noreset', sys.executable,
                            os.path.abspath(__file__), '--inner'] + sys.argv[1:], timeout=1200)
        failures = [] if p.returncode == 0 else ['the X11 part failed (above)']
        failures += wayland(args)
    for f in failures:
        print('FAIL:', f)
    print('vkcube: ' + ('OK' if not failures else f'{len(failures)} failure(s)'))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
