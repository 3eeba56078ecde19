#!/usr/bin/env python3
"""A missing device under test is a failure with a reason, never a silent skip.

Checks the exact outcome instead of "any non-zero exit" (meson's should_fail), so that a crash or a sanitizer
finding (tools/run_sanitizers.sh makes those exit 66) cannot pass for the expected failure.
usage: test_absent_device.py TILEVK_CTS
"""
import subprocess
import sys


def main() -> int:
    cts = sys.argv[1]
    r = subprocess.run([cts, '--device', 'no-such-device', '--ref', 'llvmpipe', '--filter', 'api.smoke.*'],
                       capture_output=True, text=True, timeout=600)
    out = r.stdout + r.stderr
    problems = []
    if r.returncode != 1:
        problems.append(f'exit status {r.returncode}, expected 1 (every case failed)')
    if "no Vulkan device named '*no-such-device*'" not in out:
        problems.append('no failure reason naming the missing device')
    if 'tilevk-cts: 0 passed,' not in out or ' 0 not supported' not in out:
        problems.append('summary does not say 0 passed and 0 not supported')
    if problems:
        print(out[-4000:])
        for p in problems:
            print('FAIL:', p)
        return 1
    print('absent device: every case failed with the reason, exit status 1')
    return 0


if __name__ == '__main__':
    sys.exit(main())
