#!/usr/bin/python3
"""icd/gen/gen_entrypoints.py's rules, on the real vk.xml with made-up driver sources:
a listed extension needs all of its commands written; a written command must be core or of a listed extension;
aliases of a listed extension point at the core function; require blocks that depend on a version or extension
tilevk does not expose bring nothing; the one-value vkCmdSet* of --simple-commands are written by the generator."""
import os
import subprocess
import sys
import tempfile

GEN, XML = sys.argv[1], sys.argv[2]


def run(max_version, extensions, commands, simple=None):
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, 'src.cpp')
        with open(src, 'w') as f:
            f.write('\n'.join(f'VKAPI_ATTR void VKAPI_CALL tvk_{c}(' for c in commands))
        ext = os.path.join(d, 'extensions.txt')
        with open(ext, 'w') as f:
            f.write('# comment\n' + '\n'.join(extensions) + '\n')
        h, cpp = os.path.join(d, 'e.h'), os.path.join(d, 'e.cpp')
        more = []
        if simple is not None:
            more = ['--simple-commands', os.path.join(d, 'simple.txt')]
            with open(more[1], 'w') as f:
                f.write('# comment\n' + '\n'.join(simple) + '\n')
        p = subprocess.run([sys.executable, GEN, '--xml', XML, '--max-version', max_version, '--extensions', ext,
                            *more, '--out-h', h, '--out-cpp', cpp, src], capture_output=True, text=True)
        out = open(cpp).read() if p.returncode == 0 else ''
        return p.returncode, p.stderr, out


failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


# Core 1.0 needs all 1.0 commands: one command alone is refused for every missing one.
rc, err, _ = run('1.0', [], ['CreateInstance'])
check(rc == 1 and 'vkCreateDevice: required by core Vulkan 1.0' in err, 'missing core command refused')

# Take every 1.0 command from the registry the way the generator reads it, to build a valid driver.
sys.path.insert(0, os.path.dirname(GEN))
import gen_entrypoints as g  # noqa: E402

reg = g.Registry(XML)
core10 = [n[2:] for n, v in reg.core.items() if v == (1, 0)]
rc, err, out = run('1.0', [], core10)
check(rc == 0, f'all of 1.0 accepted: {err}')
check('vkGetPhysicalDeviceProperties2KHR' not in out, 'no extension alias without its extension')

# An extension with a command missing is refused, naming the command and the extension.
rc, err, _ = run('1.0', ['VK_KHR_get_physical_device_properties2'], core10)
check(rc == 1 and 'tvk_GetPhysicalDeviceProperties2 is not written' in err, 'incomplete extension refused')

# Listed and complete: the KHR alias points at the core-named function, the core name is not exposed at 1.0.
props2 = ['GetPhysicalDeviceFeatures2', 'GetPhysicalDeviceProperties2', 'GetPhysicalDeviceFormatProperties2',
          'GetPhysicalDeviceImageFormatProperties2', 'GetPhysicalDeviceQueueFamilyProperties2',
          'GetPhysicalDeviceMemoryProperties2', 'GetPhysicalDeviceSparseImageFormatProperties2']
rc, err, out = run('1.0', ['VK_KHR_get_physical_device_properties2'], core10 + props2)
check(rc == 0, f'complete extension accepted: {err}')
check('{"vkGetPhysicalDeviceProperties2KHR", reinterpret_cast<PFN_vkVoidFunction>(&tvk_GetPhysicalDeviceProperties2)'
      in out, 'alias maps to the core function')
check('{"vkGetPhysicalDeviceProperties2", ' not in out, 'the 1.1 name is not exposed by a 1.0 driver')
check('{"VK_KHR_get_physical_device_properties2", 2, false}' in out, 'extension table has spec version and kind')

# An extension without the extensions it requires is refused (VK_EXT_depth_clip_control needs
# VK_KHR_get_physical_device_properties2), and accepted once that is listed.
rc, err, _ = run('1.0', ['VK_EXT_depth_clip_control'], core10)
check(rc == 1 and 'requires VK_KHR_get_physical_device_properties2' in err, 'missing extension dependency refused')
rc, err, _ = run('1.0', ['VK_KHR_get_physical_device_properties2', 'VK_EXT_depth_clip_control'], core10 + props2)
check(rc == 0, f'extension with its dependency accepted: {err}')

# A written command that nothing exposes is refused.
rc, err, _ = run('1.0', [], core10 + ['CreateSwapchainKHR'])
check(rc == 1 and 'vkCreateSwapchainKHR: neither core' in err, 'stray extension command refused')

# An unknown extension name is refused.
rc, err, _ = run('1.0', ['VK_TILEVK_not_real'], core10)
check(rc == 1 and 'not a Vulkan extension' in err, 'unknown extension refused')

# --simple-commands: a listed command counts as written and gets its definition; one that takes more than one scalar
# value, or one that a source also writes, is refused.
without = [c for c in core10 if c not in ('CmdSetLineWidth', 'CmdSetBlendConstants')]
rc, err, out = run('1.0', [], without, ['vkCmdSetLineWidth record kLineWidth',
                                        'vkCmdSetBlendConstants refuse someFeature'])
check(rc == 0, f'simple commands accepted: {err}')
check('VKAPI_ATTR void VKAPI_CALL tvk_CmdSetLineWidth(VkCommandBuffer commandBuffer, float lineWidth) {\n'
      '    record_dynamic_value(commandBuffer, DynamicState::kLineWidth, uint32_t(lineWidth));\n}' in out,
      'a record line is defined with the value it records')
check('VKAPI_ATTR void VKAPI_CALL tvk_CmdSetBlendConstants(VkCommandBuffer, const float[4]) {\n'
      '    refuse_dynamic_command("vkCmdSetBlendConstants", "someFeature");\n}' in out,
      'a refuse line logs naming the feature, its parameters unnamed')
rc, err, _ = run('1.0', [], without + ['CmdSetLineWidth'], ['vkCmdSetLineWidth record kLineWidth',
                                                            'vkCmdSetBlendConstants record kBlendConstants'])
check(rc == 1 and 'vkCmdSetBlendConstants does not set one scalar value' in err, 'an array value is not recorded')
check('vkCmdSetLineWidth: written in a source and listed' in err, 'a command written twice is refused')

if failures:
    print('FAILED:\n  ' + '\n  '.join(failures))
    sys.exit(1)
print('gen_entrypoints: all rules hold')
