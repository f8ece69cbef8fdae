/**
 * Completion in a `.scenario` file (docs/simulation.md "Editing scenarios"). The context is read
 * from the text of the line before the cursor (a line being typed does not parse yet): directive
 * keywords at the start of a line, then what the project has at that place — module names and
 * `MODULE:` -> its out event ports, `SUP.` -> functions -> rules, schema names, locals, parameter
 * names, the string values the rules compare a port with. Never throws.
 */
import { CompletionItemKind, type CompletionItem, type Position, type Range } from 'vscode-languageserver-types';
import { eventPortsOf, localsOf, rulesOf } from '../../model/blocks.js';
import { portsOfKind } from '../../model/ports.js';
import { typeName, typeOf, type CactalType } from '../../model/types.js';
import { defaultValue, formatConstant, type ConstantValue } from '../../model/values.js';
import type { Port } from '../../generated/ast.js';
import { stringValuesOf, type ScenarioNames } from './scenario-names.js';

/** Lines longer than this get no completion (the format is one short directive per line). */
const MAX_LINE = 4096;

const IDENT = '[A-Za-z_][A-Za-z0-9_]*';

/** Directives at the start of a line (after an optional `t=TIME`). */
const DIRECTIVES: Array<{ label: string; detail: string; header?: boolean }> = [
    { label: 'start', detail: 'start SUP.function(param = value, ...): a control tool starts a supervision function' },
    { label: 'stop', detail: 'stop SUP.function: a control tool stops it' },
    { label: 'expect', detail: 'expect rule|schema|function|module|local|deadline misses|overruns ...: checked at this time' },
    { label: 'crash', detail: 'crash MODULE: it stops and never acknowledges a release again' },
    { label: 'finish', detail: 'finish MODULE [after TIME [once]]: the asynchronous module\'s own code ends its run (now, or each run that long after its start)' },
    { label: 'exec', detail: 'exec MODULE TIME [once]: execution time of each release of a synchronous module, of each event an asynchronous module handles' },
    { label: 'scenario', detail: 'scenario TITLE: the scenario\'s title (header line)', header: true },
    { label: 'until', detail: 'until TIME: the virtual end of the scenario (header line)', header: true },
];

const EXPECTATIONS: Array<{ label: string; detail: string }> = [
    { label: 'rule', detail: 'expect rule SUP.function.RULE active|inactive' },
    { label: 'schema', detail: 'expect schema NAME active|inactive' },
    { label: 'function', detail: 'expect function SUP.function running|stopped' },
    { label: 'module', detail: 'expect module NAME running|stopped' },
    { label: 'local', detail: 'expect local [SUP.function.]name == value' },
    { label: 'deadline misses', detail: 'expect deadline misses SCHEMA == N: the periodic schema\'s deadline misses (ORD:0) since the scenario started' },
    { label: 'overruns', detail: 'expect overruns SCHEMA == N: the periodic schema\'s overruns (ticks skipped) since the scenario started' },
];

/** A value in the scenarios' spelling (docs/simulation.md: `{1.0, {2, "a"}, 3}`, spaced after commas). */
function valueText(v: ConstantValue): string {
    return v.kind === 'struct' ? `{${v.fields.map((f) => valueText(f.value)).join(', ')}}` : formatConstant(v);
}

function portDetail(port: Port, owner: string): string {
    return `out event :${port.index} ${typeName(typeOf(port.type))} ${port.name} of ${owner}`;
}

/** Removes a `#` comment outside strings; undefined when the cursor is inside the comment. */
function codeBefore(text: string): string | undefined {
    let inString = false;
    for (let i = 0; i < text.length; i++) {
        const c = text[i];
        if (inString) {
            if (c === '\\') i++;
            else if (c === '"') inString = false;
        } else if (c === '"') inString = true;
        else if (c === '#') return undefined;
    }
    return text;
}

export function scenarioCompletion(text: string, position: Position, names: ScenarioNames): CompletionItem[] {
    try {
        return completeUnguarded(text, position, names);
    } catch {
        return [];
    }
}

/** The completion itself; `scenarioCompletion` guards it (exported for the property test, which must see a throw). */
export function completeUnguarded(text: string, position: Position, names: ScenarioNames): CompletionItem[] {
    const lines = text.split(/\r?\n/);
    const lineText = lines[position.line];
    if (lineText === undefined || lineText.length > MAX_LINE) return [];
    const before = codeBefore(lineText.slice(0, Math.min(position.character, lineText.length)));
    if (before === undefined) return [];

    // The word being typed (an identifier, or a string being opened) is what the items replace.
    const partial = /"?[A-Za-z0-9_]*$/.exec(before)![0];
    const range: Range = { start: { line: position.line, character: before.length - partial.length }, end: position };
    const items: CompletionItem[] = [];
    const add = (label: string, kind: CompletionItemKind, detail?: string, insert = label, sortText?: string) => {
        items.push({ label, kind, detail, textEdit: { range, newText: insert }, filterText: partial.startsWith('"') ? `"${label.replace(/^"/, '')}` : undefined, sortText });
    };
    const modules = () => names.modules.forEach((m, n) => add(n, CompletionItemKind.Class, `${m.kind} module`));
    const supervisors = (suffix = '') => names.supervisors.forEach((_s, n) => add(n, CompletionItemKind.Class, 'supervisor', n + suffix));
    const functionsOf = (sup: string) => names.supervisors.get(sup)?.functions.forEach((f) =>
        add(f.name, CompletionItemKind.Function, `${sup}.${f.name}(${f.parameters.map((p) => `${typeName(typeOf(p.type))} ${p.name}`).join(', ')})`));
    const words = (...list: string[]) => list.forEach((w) => add(w, CompletionItemKind.Keyword));
    /** The type's default value as a template to edit (one element per field, in declaration order). */
    const template = (type: CactalType, what: string) => {
        const v = defaultValue(type);
        if (v) add(valueText(v), CompletionItemKind.Snippet, `${typeName(type)} ${what}: the type's default value, to edit`, valueText(v), 'z');
    };

    // Optional time prefix: `t=TIME ` (being typed: nothing to offer).
    const timed = new RegExp('^\\s*t\\s*=\\s*\\S*\\s+').exec(before);
    if (!timed && /^\s*t\s*=\s*\S*$/.test(before)) return [];
    let rest = timed ? before.slice(timed[0].length) : before;

    let m: RegExpExecArray | null;
    // First word of the directive.
    if (/^\s*[A-Za-z_0-9]*$/.test(rest)) {
        if (!timed) add('t=', CompletionItemKind.Keyword, 't=TIME: the virtual time of this line (0, 250us, 300ms, 1.5s)', 't=', '0');
        for (const d of DIRECTIVES) if (!(timed && d.header)) add(d.label, CompletionItemKind.Keyword, d.detail, d.label, `1${d.label}`);
        names.modules.forEach((mod, n) => add(`${n}:`, CompletionItemKind.Class, `event of ${mod.kind} module ${n}: ${n}:PORT value`, `${n}:`, `2${n}`));
        names.supervisors.forEach((_s, n) => {
            if (eventPortsOf(_s).some((p) => p.direction === 'out')) add(`${n}:`, CompletionItemKind.Class, `event of supervisor ${n}: ${n}:PORT value`, `${n}:`, `2${n}`);
        });
        add('ORD:', CompletionItemKind.Class, 'ORD:0 "schema" (deadline miss), ORD:1 "schema" (conflict)', 'ORD:', '3ORD');
        return items;
    }
    // MODULE:  -> its out event ports.
    if ((m = new RegExp(`^\\s*(${IDENT})\\s*:\\s*[0-9]*$`).exec(rest))) {
        const src = m[1]!;
        if (src === 'ORD') {
            add('0', CompletionItemKind.Property, 'ORD:0 "schema": deadline miss of that schema');
            add('1', CompletionItemKind.Property, 'ORD:1 "schema": conflict of that schema');
            return items;
        }
        const owner = names.modules.get(src) ?? names.supervisors.get(src);
        if (!owner) return [];
        for (const p of portsOfKind(owner, 'event', 'out')) add(String(p.index), CompletionItemKind.Property, portDetail(p, src));
        return items;
    }
    // MODULE:PORT [name =] value  -> the port's name, then the string values the rules test.
    if ((m = new RegExp(`^\\s*(${IDENT})\\s*:\\s*([0-9]+)\\s+(?:(${IDENT})\\s*=\\s*)?("?[A-Za-z0-9_]*)$`).exec(rest))) {
        const src = m[1]!;
        const port = Number(m[2]);
        if (src === 'ORD') {
            names.schemas.forEach((s, n) => add(`"${n}"`, CompletionItemKind.Value, `${s.kind} schema`));
            return items;
        }
        const owner = names.modules.get(src) ?? names.supervisors.get(src);
        const p = owner && portsOfKind(owner, 'event', 'out').find((x) => x.index === port);
        if (!p) return [];
        if (!m[3] && !m[4]!.startsWith('"')) add(`${p.name} =`, CompletionItemKind.Variable, portDetail(p, src), `${p.name} = `);
        for (const v of stringValuesOf(names, src, port)) add(JSON.stringify(v), CompletionItemKind.Value, `a value the rules compare ${src}:${port} with`);
        if (!m[4]) template(typeOf(p.type), p.name);
        return items;
    }
    // start / stop SUP.fn(...)
    if ((m = /^\s*(start|stop)\s+([A-Za-z0-9_]*)$/.exec(rest))) {
        supervisors('.');
        return items;
    }
    if ((m = new RegExp(`^\\s*(start|stop)\\s+(${IDENT})\\.[A-Za-z0-9_]*$`).exec(rest))) {
        functionsOf(m[2]!);
        return items;
    }
    if ((m = new RegExp(`^\\s*start\\s+(${IDENT})\\.(${IDENT})\\s*\\((?:[^)]*,)?\\s*(${IDENT})\\s*=\\s*$`).exec(rest))) {
        const p = names.supervisors.get(m[1]!)?.functions.find((x) => x.name === m![2])?.parameters.find((x) => x.name === m![3]);
        if (p) template(typeOf(p.type), p.name);
        return items;
    }
    if ((m = new RegExp(`^\\s*start\\s+(${IDENT})\\.(${IDENT})\\s*\\((?:[^)]*,)?\\s*[A-Za-z0-9_]*$`).exec(rest))) {
        const f = names.supervisors.get(m[1]!)?.functions.find((x) => x.name === m![2]);
        f?.parameters.forEach((p) => add(p.name, CompletionItemKind.Variable, `${typeName(typeOf(p.type))} ${p.name}`, `${p.name} = `));
        return items;
    }
    // crash / finish / exec MODULE (finish: asynchronous modules; exec: a synchronous one's releases, an asynchronous one's event handling)
    if ((m = /^\s*(crash|finish|exec)\s+[A-Za-z0-9_]*$/.exec(rest))) {
        const kind = m[1] === 'finish' ? 'asynchronous' : undefined;
        names.modules.forEach((mod, n) => {
            if (!kind || mod.kind === kind) add(n, CompletionItemKind.Class, `${mod.kind} module`);
        });
        return items;
    }
    // finish MODULE |: its run ends now, or `after TIME` each run
    if (/^\s*finish\s+[A-Za-z_]\w*\s+[a-z]*$/.test(rest)) {
        add('after', CompletionItemKind.Keyword, 'finish MODULE after TIME [once]: each of its runs from now on (once: the next one) ends TIME after its start');
        return items;
    }
    // expect [at TIME] WHAT ...
    const ex = new RegExp('^\\s*expect\\s+(?:at\\s+\\S+\\s+)?').exec(rest);
    if (!ex) return [];
    const hasAt = /^\s*expect\s+at\s/.test(rest);
    rest = rest.slice(ex[0].length);
    if (/^[A-Za-z0-9_]*$/.test(rest)) {
        for (const e of EXPECTATIONS) add(e.label, CompletionItemKind.Keyword, e.detail);
        if (!hasAt && !timed) add('at', CompletionItemKind.Keyword, 'expect at TIME ...: the same as t=TIME expect ...');
        return items;
    }
    if ((m = /^(rule|function)\s+[A-Za-z0-9_]*$/.exec(rest))) return supervisors('.'), items;
    if ((m = new RegExp(`^(rule|function)\\s+(${IDENT})\\.[A-Za-z0-9_]*$`).exec(rest))) return functionsOf(m[2]!), items;
    if ((m = new RegExp(`^rule\\s+(${IDENT})\\.(${IDENT})\\.[A-Za-z0-9_]*$`).exec(rest))) {
        const f = names.supervisors.get(m[1]!)?.functions.find((x) => x.name === m![2]);
        if (f) for (const r of rulesOf(f)) add(r.name, CompletionItemKind.EnumMember, `rule of ${m[1]}.${f.name}`);
        return items;
    }
    if (new RegExp(`^(rule\\s+${IDENT}\\.${IDENT}\\.${IDENT}|schema\\s+${IDENT})\\s+[A-Za-z]*$`).test(rest)) return words('active', 'inactive'), items;
    if (new RegExp(`^(function\\s+${IDENT}\\.${IDENT}|module\\s+${IDENT})\\s+[A-Za-z]*$`).test(rest)) return words('running', 'stopped'), items;
    if (/^(deadline\s+misses|overruns)\s+[A-Za-z0-9_]*$/.test(rest)) {
        names.schemas.forEach((s, n) => {
            if (s.kind === 'periodic') add(n, CompletionItemKind.Module, 'periodic schema');
        });
        return items;
    }
    if (/^deadline\s+[a-z]*$/.test(rest)) return words('misses'), items;
    if (/^schema\s+[A-Za-z0-9_]*$/.test(rest)) {
        names.schemas.forEach((s, n) => add(n, CompletionItemKind.Module, `${s.kind} schema`));
        return items;
    }
    if (/^module\s+[A-Za-z0-9_]*$/.test(rest)) return modules(), items;
    if (/^local\s+[A-Za-z0-9_]*$/.test(rest)) {
        supervisors('.');
        for (const sup of names.supervisors.values())
            for (const f of sup.functions)
                for (const l of localsOf(f)) add(l.name, CompletionItemKind.Variable, `${typeName(typeOf(l.type))} ${l.name}, local of ${sup.name}.${f.name}`);
        return items;
    }
    if ((m = new RegExp(`^local\\s+(?:(${IDENT})\\.(${IDENT})\\.)?(${IDENT})\\s*==\\s*$`).exec(rest))) {
        for (const sup of names.supervisors.values()) {
            if (m[1] && sup.name !== m[1]) continue;
            for (const f of sup.functions) {
                if (m[2] && f.name !== m[2]) continue;
                const l = localsOf(f).find((x) => x.name === m![3]);
                if (l) return template(typeOf(l.type), l.name), items;
            }
        }
        return items;
    }
    if ((m = new RegExp(`^local\\s+(${IDENT})\\.[A-Za-z0-9_]*$`).exec(rest))) return functionsOf(m[1]!), items;
    if ((m = new RegExp(`^local\\s+(${IDENT})\\.(${IDENT})\\.[A-Za-z0-9_]*$`).exec(rest))) {
        const f = names.supervisors.get(m[1]!)?.functions.find((x) => x.name === m![2]);
        if (f) for (const l of localsOf(f)) add(l.name, CompletionItemKind.Variable, `${typeName(typeOf(l.type))} ${l.name}`);
        return items;
    }
    return [];
}
