/**
 * Sandbox selection (docs/sandbox.md "Choosing a sandbox"): `auto` = bwrap when it works here, else docker when an engine
 * answers, else an error saying how to install bubblewrap. `none` only when asked for by name.
 */
import { BwrapSandbox, type BwrapOptions } from './bwrap.js';
import { DockerSandbox, type DockerOptions } from './docker.js';
import { NoSandbox } from './none.js';
import type { Sandbox, SandboxChoice, SandboxName, SandboxProbe } from './types.js';

export { SANDBOX_CHOICES } from '@contract-studio/conventions';

export class SandboxUnavailableError extends Error {}

export interface SandboxRegistryOptions {
  bwrap?: BwrapOptions;
  docker?: DockerOptions;
}

export class SandboxRegistry {
  readonly sandboxes: Record<SandboxName, Sandbox>;
  /** The Docker sandbox itself (its sweep of orphaned containers, its owner). */
  readonly docker: DockerSandbox;
  private readonly probes = new Map<SandboxName, Promise<SandboxProbe>>();

  constructor(options: SandboxRegistryOptions = {}) {
    this.docker = new DockerSandbox(options.docker);
    this.sandboxes = {
      bwrap: new BwrapSandbox(options.bwrap),
      docker: this.docker,
      none: new NoSandbox(),
    };
  }

  /** Probes once per service (docker probes are retried when they failed: an engine may start later). */
  probe(name: SandboxName): Promise<SandboxProbe> {
    let p = this.probes.get(name);
    if (!p) {
      p = this.sandboxes[name].probe();
      this.probes.set(name, p);
      void p.then((r) => {
        if (!r.available && name === 'docker') this.probes.delete(name);
      });
    }
    return p;
  }

  /** Resolves a choice to a usable sandbox, with a note saying what was picked and why. */
  async resolve(choice: SandboxChoice): Promise<{ sandbox: Sandbox; note: string; warnings: string[] }> {
    if (choice === 'auto') {
      const bw = await this.probe('bwrap');
      if (bw.available) return { sandbox: this.sandboxes.bwrap, note: `sandbox auto: picked bwrap (${bw.detail})`, warnings: [] };
      const dk = await this.probe('docker');
      if (dk.available) {
        return { sandbox: this.sandboxes.docker, note: `sandbox auto: picked docker (${dk.detail}); bwrap: ${bw.detail}`, warnings: [] };
      }
      throw new SandboxUnavailableError(
        `no sandbox available: ${bw.detail}; docker: ${dk.detail}. Install bubblewrap ("sudo apt-get install bubblewrap") or start a Docker engine; "--sandbox none" runs without isolation`,
      );
    }
    const sandbox = this.sandboxes[choice];
    const p = await this.probe(choice);
    if (!p.available) throw new SandboxUnavailableError(`sandbox ${choice} unavailable: ${p.detail}`);
    const warnings =
      choice === 'none' ? [`sandbox none: not enforced: ${sandbox.unenforced.join(', ')} (only wall time and output limits hold)`] : [];
    return { sandbox, note: `sandbox ${choice} (${p.detail})`, warnings };
  }
}
