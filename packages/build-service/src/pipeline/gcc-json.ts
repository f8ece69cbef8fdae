/**
 * gcc's `-fdiagnostics-format=json` lines (one JSON array per compilation), read from a sandbox's
 * stderr. That stderr is untrusted text: user code can print any JSON-looking line (an `__asm__`
 * `.warning`, a `#warning`, a program run by make). Every field is checked against ONE declared
 * schema, bounded in depth, count and length (SERVICE_BOUNDS, docs/sandbox.md "Limits"); a line
 * that does not match is not a diagnostic line, it stays a plain text line. Nothing here throws.
 */
import { z } from 'zod';
import { SERVICE_BOUNDS } from '../limits.js';
import { located, severityOf, type DiagnosticContext, type GccDiagnostic } from './gcc-diagnostics.js';
import { completeDiagnosticsPrefix } from './gcc-json-salvage.js';
import { parseGccJson } from './gcc-json-controls.js';

const text = z.string().max(SERVICE_BOUNDS.diagnosticTextChars);
/** Line and column numbers: non-negative integers of a plausible size. */
const count = z.number().int().min(0).max(2 ** 31 - 1);

const position = z.object({ file: text.optional(), line: count.optional(), column: count.optional() });
const location = z.object({ caret: position.optional(), finish: position.optional() });

type JsonDiagnostic = {
  kind?: string | undefined;
  message?: string | undefined;
  option?: string | undefined;
  locations?: z.infer<typeof location>[] | undefined;
  children?: JsonDiagnostic[] | undefined;
};

/** The schema of one diagnostic whose children may nest `depth` more levels (none at 0). */
function diagnosticSchema(depth: number): z.ZodType<JsonDiagnostic> {
  const children = depth > 0 ? z.array(diagnosticSchema(depth - 1)) : z.array(z.never());
  return z.object({
    kind: z.string().max(64).optional(),
    message: text.optional(),
    option: text.optional(),
    locations: z.array(location).max(SERVICE_BOUNDS.diagnosticChildren).optional(),
    children: children.max(SERVICE_BOUNDS.diagnosticChildren).optional(),
  });
}

/** One line of gcc JSON output: the declared shape every parsed field is checked against. */
export const GCC_JSON_LINE = z.array(diagnosticSchema(SERVICE_BOUNDS.diagnosticDepth)).max(SERVICE_BOUNDS.diagnosticsPerJsonLine);

/** The message of a diagnostic a cut line left open before its `message` (gcc 12 writes it last). */
export const MESSAGE_CUT = '(its message was cut with the line)';

function fromJson(d: JsonDiagnostic, ctx: DiagnosticContext, noMessage = ''): GccDiagnostic {
  const loc = d.locations?.[0];
  const caret = loc?.caret;
  return located(
    {
      severity: severityOf(d.kind),
      message: d.message ?? noMessage,
      ...(d.option ? { option: d.option } : {}),
      line: caret?.line ?? null,
      column: caret?.column ?? null,
      ...(loc?.finish?.line ? { endLine: loc.finish.line } : {}),
      ...(loc?.finish?.column ? { endColumn: loc.finish.column } : {}),
      children: (d.children ?? []).map((c) => fromJson(c, ctx, noMessage)),
    },
    caret?.file ?? null,
    ctx,
  );
}

/** True when a stderr line is gcc's `-fdiagnostics-format=json` output (one JSON array per compilation). */
export function looksLikeGccJson(line: string): boolean {
  return /^\[\s*(\]|\{\s*"kind")/.test(line.slice(0, 64));
}

/**
 * A compilation's diagnostics as they are reported: a child that is no note (gcc 12 puts every
 * preprocessor diagnostic of a compilation, `#warning` or `#error`, and the errors after them, in
 * the first one's `children`) is a diagnostic of its own, so that an error is counted as one
 * wherever gcc nested it; in gcc's order.
 */
function asReported(diagnostics: GccDiagnostic[]): GccDiagnostic[] {
  const out: GccDiagnostic[] = [];
  const add = (d: GccDiagnostic): void => {
    const own = d.children.filter((c) => c.severity !== 'note');
    out.push(own.length ? { ...d, children: d.children.filter((c) => c.severity === 'note') } : d);
    for (const c of own) add(c);
  };
  for (const d of diagnostics) add(d);
  return out;
}

/**
 * A compilation's diagnostics as the job keeps them: the errors first, each in gcc's order (a job
 * keeps diagnosticsPerJob: a compilation's hundreds of warnings must not push its error out).
 */
export function errorsFirst(diagnostics: readonly GccDiagnostic[]): GccDiagnostic[] {
  return [...diagnostics.filter((d) => d.severity === 'error'), ...diagnostics.filter((d) => d.severity !== 'error')];
}

function parseDiagnostics(text: string, ctx: DiagnosticContext, noMessage = ''): GccDiagnostic[] | null {
  // a raw control character of a message (gcc writes a `#warning`'s as they are) is read as its escape
  const data = parseGccJson(text);
  if (data === undefined) return null;
  const parsed = GCC_JSON_LINE.safeParse(data);
  if (!parsed.success) return null;
  return asReported(parsed.data.map((d) => fromJson(d, ctx, noMessage)));
}

/** Parses one line of gcc JSON diagnostics; null when it is not valid JSON of the declared shape. */
export function parseGccJsonLine(line: string, ctx: DiagnosticContext): GccDiagnostic[] | null {
  return parseDiagnostics(line, ctx);
}

/**
 * The complete diagnostics of a gcc JSON line that was cut (gcc-json-salvage.ts), with the number
 * of characters they were read from; null when none of it is a complete diagnostic of the declared
 * shape. The caller says the cut: what followed is lost.
 */
export function parseCutGccJsonLine(line: string, ctx: DiagnosticContext): { diagnostics: GccDiagnostic[]; readChars: number } | null {
  const prefix = completeDiagnosticsPrefix(line);
  if (prefix === null) return null;
  const diagnostics = parseDiagnostics(prefix, ctx, MESSAGE_CUT);
  return diagnostics?.length ? { diagnostics, readChars: prefix.length } : null;
}

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null && !Array.isArray(v);

/**
 * A diagnostics list (a line's, or a diagnostic's `children`, recursively) cut to
 * diagnosticsPerJsonLine (children: diagnosticChildren), its errors kept first and the others
 * after them, each in gcc's order; how many were left out. Only the raw JSON is looked at here:
 * the declared schema then checks what is kept.
 */
function withinBounds(list: unknown[], bound: number, depth: number): { list: unknown[]; left: number } {
  let left = 0;
  const trimmed = list.map((d) => {
    if (!isObject(d) || depth <= 0 || !Array.isArray(d.children)) return d;
    const children = withinBounds(d.children, SERVICE_BOUNDS.diagnosticChildren, depth - 1);
    left += children.left;
    return { ...d, children: children.list };
  });
  if (trimmed.length <= bound) return { list: trimmed, left };
  const isError = (d: unknown): boolean => isObject(d) && d.kind === 'error';
  const keep = new Set<number>();
  trimmed.forEach((d, i) => keep.size < bound && isError(d) && keep.add(i));
  trimmed.forEach((d, i) => keep.size < bound && !isError(d) && keep.add(i));
  return { list: trimmed.filter((_, i) => keep.has(i)), left: left + trimmed.length - keep.size };
}

/**
 * A whole gcc JSON line holding more diagnostics than the bounds read (a compilation's 1,000
 * warnings and its error): read up to the bounds, its errors first, with how many were left out;
 * null when it is no such line (the caller says what was left out: the errors are never among them
 * unless they alone pass the bound).
 */
export function parseOverfullGccJsonLine(line: string, ctx: DiagnosticContext): { diagnostics: GccDiagnostic[]; left: number } | null {
  const data = parseGccJson(line);
  if (!Array.isArray(data)) return null;
  const { list, left } = withinBounds(data, SERVICE_BOUNDS.diagnosticsPerJsonLine, SERVICE_BOUNDS.diagnosticDepth);
  if (!left) return null;
  const parsed = GCC_JSON_LINE.safeParse(list);
  if (!parsed.success) return null;
  return { diagnostics: asReported(parsed.data.map((d) => fromJson(d, ctx))), left };
}
