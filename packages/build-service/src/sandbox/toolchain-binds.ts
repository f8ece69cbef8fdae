/**
 * The host toolchain as a bubblewrap sandbox sees it, read-only: `/usr`, the top-level `/bin`,
 * `/sbin`, `/lib*` (real folders bound, usr-merged links recreated as links), and from `/etc` only
 * what the loader and Debian's alternatives need. Shared by the build sandbox (bwrap.ts) and the
 * simulator's confinement (`@contract-studio/build-service/toolchain`), so both show the same host.
 */
import { existsSync, lstatSync, readlinkSync } from 'node:fs';

export function toolchainBinds(): string[] {
  const args = ['--ro-bind', '/usr', '/usr'];
  for (const top of ['/bin', '/sbin', '/lib', '/lib32', '/lib64', '/libx32']) {
    let st;
    try {
      st = lstatSync(top);
    } catch {
      continue;
    }
    if (st.isSymbolicLink()) args.push('--symlink', readlinkSync(top), top);
    else if (st.isDirectory()) args.push('--ro-bind', top, top);
  }
  for (const f of ['/etc/ld.so.cache', '/etc/ld.so.conf', '/etc/alternatives', '/etc/localtime']) {
    if (existsSync(f)) args.push('--ro-bind', f, f);
  }
  return args;
}
