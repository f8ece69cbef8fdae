/**
 * A rename carried into the project's `.scenario` files (docs/simulation.md "Scenario files"): the
 * names a scenario writes follow the rename, token by token, from the scenario parser's spans (never
 * a text search): a module or supervisor (`M:P`, `crash M`, `exec M`, `expect module M`, `start
 * SUP.fn`, `expect rule SUP.fn.RULE`, ...), a schema (`expect schema S`, `ORD:0 "S"`), a supervision
 * function (`SUP.fn` of that supervisor), an out event port's variable name (`M:P name = value` of
 * that module), an enumeration or one of its members (`Mode.AUTO` values), a rule label or a local of a supervision
 * function (`expect rule SUP.fn.RULE`, `expect local [SUP.fn.]x`), a parameter of one (`start
 * SUP.fn(x = ...)`). `contract rename` and the IDE's rename
 * (POST /api/rename-entity) both use it.
 */
import { closeSync, constants, fstatSync, openSync, readdirSync, readFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { parseScenario, type ScenarioValue, type SourceSpan, type Step } from '../scenario/parse.js';

export interface ScenarioRename {
    /**
     * The rename's kind word: `module`, `supervisor`, `schema`, `supervision function`, `port`,
     * `datatype`, `enumeration`, `enumeration member`, `rule label`, `local`, `function parameter` (any other: nothing to rename).
     */
    kind: string;
    oldName: string;
    newName: string;
    /**
     * For a port: its module (or supervisor); for a supervision function: its supervisor; for a
     * rule label, a local or a function parameter: its function as `SUP.function`; for an
     * enumeration member: its enumeration.
     */
    owner?: string;
}

export interface ScenarioEdit {
    /** Path relative to the project folder. */
    file: string;
    line: number;
    /** The line before and after. */
    before: string;
    after: string;
}

export interface ScenarioFileChange {
    /** Path relative to the project folder. */
    file: string;
    path: string;
    /** The text read (a writer can check the file did not change since). */
    original: string;
    /** The new text. */
    text: string;
    edits: ScenarioEdit[];
}

const MAX_DEPTH = 6;
const MAX_FILES = 10_000;
/** A scenario file larger than this is left as it is (the simulator reads 256 Ki characters at most). */
const MAX_SCENARIO_BYTES = 1 << 20;

/** A scenario file's text, read without following a link; undefined if it is not a regular file of a sane size. */
function readScenario(path: string): string | undefined {
    let fd: number;
    try {
        fd = openSync(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    } catch {
        return undefined;
    }
    try {
        const st = fstatSync(fd);
        if (!st.isFile() || st.size > MAX_SCENARIO_BYTES) return undefined;
        return readFileSync(fd, 'utf8');
    } catch {
        return undefined;
    } finally {
        closeSync(fd);
    }
}

/**
 * The `.scenario` files of the project folder `dir`: in it and its subfolders, except the generated
 * tree, hidden folders, `node_modules`, and subfolders that are projects of their own (they hold
 * `.contract` files: their scenarios are about that project). Links are not followed.
 */
export function projectScenarios(dir: string, skip: string[]): string[] {
    const found: string[] = [];
    const walk = (abs: string, depth: number) => {
        let entries;
        try {
            entries = readdirSync(abs, { withFileTypes: true });
        } catch {
            return;
        }
        if (depth > 0 && entries.some((e) => e.isFile() && e.name.endsWith('.contract'))) return;
        for (const e of entries.sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0))) {
            if (found.length >= MAX_FILES) return;
            const child = join(abs, e.name);
            if (e.isFile() && e.name.endsWith('.scenario')) found.push(child);
            else if (e.isDirectory() && depth < MAX_DEPTH && !e.name.startsWith('.') && e.name !== 'node_modules' && !skip.includes(child)) walk(child, depth + 1);
        }
    };
    walk(dir, 0);
    return found;
}

interface Replacement {
    span: SourceSpan;
    /** The text expected at the span's start (checked before replacing). */
    from: string;
    to: string;
}

function valueReplacements(value: ScenarioValue | undefined, r: ScenarioRename, out: Replacement[]): void {
    if (!value) return;
    if (value.kind === 'struct') for (const e of value.elements) valueReplacements(e, r, out);
    if (value.kind === 'enum' && value.enumName === r.oldName && (r.kind === 'datatype' || r.kind === 'enumeration')) {
        out.push({ span: value.span, from: r.oldName, to: r.newName });
    }
    // `Mode.AUTO` of a renamed member AUTO of Mode: the member's part of the value
    if (value.kind === 'enum' && r.kind === 'enumeration member' && value.enumName === r.owner && value.member === r.oldName && value.text === `${value.enumName}.${value.member}`) {
        out.push({ span: { ...value.span, column: value.span.column + value.enumName.length + 1 }, from: r.oldName, to: r.newName });
    }
}

/** The spans of one step naming the renamed entity. */
function stepReplacements(step: Step, r: ScenarioRename): Replacement[] {
    const out: Replacement[] = [];
    const name = (n: { text: string; span: SourceSpan } | undefined, kinds: string[]) => {
        if (n && n.text === r.oldName && kinds.includes(r.kind)) out.push({ span: n.span, from: r.oldName, to: r.newName });
    };
    const owned = (owner: { text: string } | undefined, n: { text: string; span: SourceSpan } | undefined, kind: string) => {
        if (owner && owner.text === r.owner && n && n.text === r.oldName && r.kind === kind) out.push({ span: n.span, from: r.oldName, to: r.newName });
    };
    const MOD = ['module', 'supervisor'];
    /** A name of a supervision function's (`SUP.fn.NAME`, `start SUP.fn(NAME = ...)`): renamed when SUP.fn is the owner. */
    const inFunction = (sup: { text: string } | undefined, fn: { text: string } | undefined, n: { text: string; span: SourceSpan } | undefined, kind: string) => {
        if (sup && fn && `${sup.text}.${fn.text}` === r.owner && n && n.text === r.oldName && r.kind === kind) out.push({ span: n.span, from: r.oldName, to: r.newName });
    };
    switch (step.kind) {
        case 'event':
            name(step.module, MOD);
            owned(step.module, step.portName, 'port');
            // ORD:0 "schema" / ORD:1 "schema": the schema's name as a string
            if (step.module.text === 'ORD' && r.kind === 'schema' && step.value?.kind === 'string' && step.value.value === r.oldName) {
                const q = step.value.text[0]!;
                if (step.value.text === `${q}${r.oldName}${q}`) out.push({ span: { ...step.value.span, column: step.value.span.column + 1 }, from: r.oldName, to: r.newName });
            }
            valueReplacements(step.value, r, out);
            break;
        case 'start':
            name(step.supervisor, MOD);
            owned(step.supervisor, step.function, 'supervision function');
            for (const a of step.args) {
                inFunction(step.supervisor, step.function, a.name, 'function parameter');
                valueReplacements(a.value, r, out);
            }
            break;
        case 'stop':
            name(step.supervisor, MOD);
            owned(step.supervisor, step.function, 'supervision function');
            break;
        case 'crash':
        case 'finish':
        case 'exec':
            name(step.module, MOD);
            break;
        case 'expect': {
            const x = step.expectation;
            if (x.kind === 'schema' || x.kind === 'count') name(x.schema, ['schema']);
            else if (x.kind === 'module') name(x.module, MOD);
            else if (x.kind === 'local' && !x.supervisor) {
                // a bare local names the one function that has it (else the scenario is in error)
                if (r.kind === 'local' && x.local.text === r.oldName) out.push({ span: x.local.span, from: r.oldName, to: r.newName });
                valueReplacements(x.value, r, out);
            } else {
                name(x.supervisor, MOD);
                owned(x.supervisor, x.function, 'supervision function');
                if (x.kind === 'rule') inFunction(x.supervisor, x.function, x.rule, 'rule label');
                if (x.kind === 'local') {
                    inFunction(x.supervisor, x.function, x.local, 'local');
                    valueReplacements(x.value, r, out);
                }
            }
            break;
        }
    }
    return out;
}

/**
 * The new texts of the scenario files that name the renamed entity (files that do not change are
 * not listed). Each replaced token is checked to be the old name where the parser put it.
 */
export function renameInScenarios(dir: string, files: string[], r: ScenarioRename): ScenarioFileChange[] {
    const changes: ScenarioFileChange[] = [];
    for (const path of files) {
        const text = readScenario(path);
        if (text === undefined || !text.includes(r.oldName)) continue;
        const parsed = parseScenario(text);
        const replacements = parsed.steps.flatMap((s) => stepReplacements(s, r));
        if (replacements.length === 0) continue;
        const lines = text.split('\n');
        const byLine = new Map<number, Replacement[]>();
        for (const rep of replacements) byLine.set(rep.span.line, [...(byLine.get(rep.span.line) ?? []), rep]);
        const file = relative(dir, path);
        const edits: ScenarioEdit[] = [];
        for (const [line, reps] of [...byLine.entries()].sort((a, b) => a[0] - b[0])) {
            const before = lines[line - 1];
            if (before === undefined) continue;
            let after = before;
            // right to left, so that earlier columns stay valid
            for (const rep of reps.sort((a, b) => b.span.column - a.span.column)) {
                const at = rep.span.column - 1;
                if (after.slice(at, at + rep.from.length) !== rep.from) continue;
                after = after.slice(0, at) + rep.to + after.slice(at + rep.from.length);
            }
            if (after === before) continue;
            lines[line - 1] = after;
            edits.push({ file, line, before: before.replace(/\r$/, ''), after: after.replace(/\r$/, '') });
        }
        if (edits.length > 0) changes.push({ file, path, original: text, text: lines.join('\n'), edits });
    }
    return changes;
}
