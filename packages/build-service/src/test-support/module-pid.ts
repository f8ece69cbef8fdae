/**
 * The host pid of a module of this test process's own run (a real run, bwrap), found in /proc: a
 * test kills it from outside, as a user's `kill -9` would.
 */
import { readdirSync, readFileSync, readlinkSync } from 'node:fs';

/** The parent of every process of this host, by pid. */
function parents(): Map<number, number> {
    const out = new Map<number, number>();
    for (const d of readdirSync('/proc')) {
        if (!/^\d+$/.test(d)) continue;
        try {
            const stat = readFileSync(`/proc/${d}/stat`, 'utf8');
            out.set(Number(d), Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]));
        } catch { /* gone meanwhile */ }
    }
    return out;
}

/** The host pid of this test's run of module `name` (a descendant of this process whose executable is `…/<name>_mod/<name>`), or undefined. */
export function modulePid(name: string): number | undefined {
    const up = parents();
    const mine = (pid: number) => {
        for (let p = pid, n = 0; p > 1 && n < 64; p = up.get(p) ?? 0, n++) if (p === process.pid) return true;
        return false;
    };
    for (const pid of up.keys()) {
        let exe = '';
        try {
            exe = readlinkSync(`/proc/${pid}/exe`);
        } catch {
            continue;
        }
        if (exe.endsWith(`/${name}_mod/${name}`) && mine(pid)) return pid;
    }
    return undefined;
}

/**
 * Kills module `name` of this test's run with SIGKILL, from outside as a user's `kill -9` would,
 * `afterMs` after it is first seen running (looked for every 50 ms, for a minute at most): the
 * time of the kill (Date.now()), or 0 when it never ran.
 */
export async function killModuleOnceRunning(name: string, afterMs: number): Promise<number> {
    for (let i = 0; i < 1200; i++) {
        await new Promise((r) => setTimeout(r, 50));
        const pid = modulePid(name);
        if (pid === undefined) continue;
        await new Promise((r) => setTimeout(r, afterMs));
        process.kill(pid, 'SIGKILL');
        return Date.now();
    }
    return 0;
}
