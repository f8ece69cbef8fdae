/**
 * The "prepare" step's link to the language and code generator packages (architecture.md Seam 4),
 * loaded lazily (in the bounded worker of generate-worker.ts) so the service still builds plain
 * Makefile projects when they are absent:
 *   loadWorkspace(dir)                            -> documents + diagnostics
 *   generateArchitecture(documents, outDir) -> {created, updated, unchanged, orphaned, errors, warnings}
 */
export interface CactalProblem {
  file: string;
  line: number;
  column: number;
  severity: 'error' | 'warning' | 'info';
  message: string;
}

export interface GenerateOutcome {
  problems: CactalProblem[];
  written: number;
  unchanged: number;
}

type Loose = Record<string, unknown>;

function severityOf(raw: unknown): CactalProblem['severity'] {
  if (raw === 1 || raw === 'error') return 'error';
  if (raw === 2 || raw === 'warning') return 'warning';
  return 'info';
}

function uriToPath(uri: unknown): string {
  const s = typeof uri === 'string' ? uri : uri && typeof uri === 'object' && 'fsPath' in uri ? String((uri as Loose).fsPath) : String(uri ?? '');
  return s.startsWith('file://') ? decodeURIComponent(s.slice('file://'.length)) : s;
}

/** Normalises the diagnostics of loadWorkspace (LSP-shaped or already flat) into CactalProblems. */
export function normaliseProblems(raw: unknown, baseDir: string): CactalProblem[] {
  const out: CactalProblem[] = [];
  const rel = (p: string): string => (p.startsWith(baseDir + '/') ? p.slice(baseDir.length + 1) : p);
  const push = (file: string, d: Loose): void => {
    const range = (d.range as Loose | undefined)?.start as Loose | undefined;
    out.push({
      file: rel(file),
      line: Number(d.line ?? (range ? Number(range.line) + 1 : 0)),
      column: Number(d.column ?? (range ? Number(range.character) + 1 : 0)),
      severity: severityOf(d.severity),
      message: String(d.message ?? ''),
    });
  };
  if (Array.isArray(raw)) {
    for (const d of raw as Loose[]) {
      if (Array.isArray(d.diagnostics)) for (const x of d.diagnostics as Loose[]) push(uriToPath(d.uri ?? d.file), x);
      else push(uriToPath(d.file ?? d.uri), d);
    }
  } else if (raw && typeof raw === 'object') {
    for (const [file, list] of raw instanceof Map ? raw.entries() : Object.entries(raw as Loose)) {
      if (Array.isArray(list)) for (const d of list as Loose[]) push(uriToPath(file), d);
    }
  }
  return out;
}

/** The generator's errors and warnings (plain objects or strings) as CactalProblems. */
export function generationProblems(res: { errors?: unknown; warnings?: unknown }): CactalProblem[] {
  const problems: CactalProblem[] = [];
  for (const [list, severity] of [[res.errors, 'error'], [res.warnings, 'warning']] as const) {
    for (const e of (Array.isArray(list) ? list : []) as unknown[]) {
      const o = (typeof e === 'object' && e ? e : { message: String(e) }) as Loose;
      problems.push({
        file: String(o.file ?? o.path ?? ''),
        line: Number(o.line ?? 0),
        column: Number(o.column ?? 0),
        severity,
        message: String(o.message ?? e),
      });
    }
  }
  return problems;
}
