import type { Action, Condition, Event, PortDecl, Rule, SupervisionFunction, Supervisor, Test, TypeRef, Value } from '../../model/architecture.js';
import type { ArchitectureIndex } from '../../model/lookup.js';
import { PRIORITY } from '../../model/priorities.js';
import { isConstant, variableBlock } from './layouts.js';
import { schemaTable } from './schema-table.js';
import { TableBuilder } from './table-builder.js';
import { assignments, valueRef, valueType, type Resolver } from './value-refs.js';

/** `<SUP>_mod/vocabulary.c`: a supervisor's ports, functions, rules, conditions and actions as tables. */
export function generateSupervisorVocabulary(sup: Supervisor, priority: number, index: ArchitectureIndex): string {
    // every datatype with its field table: the rule causes of the trace show an event's value field
    // by field (`TEL:0 value={v=0.5,w=0}`), not `{16 bytes}`
    const b = new TableBuilder(index, { allFieldTables: true });
    const schemas = new Map<string, string>();
    const signatures = new Map<string, string>();
    const S = sup.name;

    const ports = (list: PortDecl[], base: string) =>
        b.array(base, 'ContractEventPort', [...list].sort((x, y) => x.index - y.index).map((p) =>
            `{${p.index}, "${p.name}", ${b.typeRef(p.type)}, ${p.initial !== undefined ? b.constant(p.type, p.initial) : 'NULL'}}`));
    const inPorts = ports(sup.eventIn, 'in_ports');
    const outPorts = ports(sup.eventOut, 'out_ports');

    const functions = sup.functions.map((fn) => functionTable(b, sup, fn, schemas, signatures));
    const fns = b.array('functions', 'ContractFunction', functions);
    b.define(`const ContractSupervisorVocabulary ${S}_VOCABULARY = {\n    CONTRACT_VOCABULARY_VERSION, "${S}", ${priority}, ${PRIORITY.interaction}, ${PRIORITY.resttime}, ${PRIORITY.critical},\n    ${sup.eventIn.length}, ${inPorts}, ${sup.eventOut.length}, ${outPorts}, ${functions.length}, ${fns}};`);
    return b.render([
        `// vocabulary.c of supervisor ${S} (generated whole from its Cactal description; format: contract/vocabulary.h)`,
        '#include <stddef.h>',
        '#include <contract/vocabulary.h>',
        '#include "suptypes.h"',
    ]);
}

function functionTable(b: TableBuilder, sup: Supervisor, fn: SupervisionFunction, schemas: Map<string, string>, signatures: Map<string, string>): string {
    const base = `${fn.name}`;
    const params = variableBlock(b, `${base}_params`, fn.parameters);
    // locals: constant initialisers are defaults; the others become local_inits (from parameters)
    const locals = variableBlock(b, `${base}_locals`, fn.locals);
    const paramResolver: Resolver = (name) => {
        const i = fn.parameters.findIndex((p) => p.name === name);
        return i < 0 ? undefined : { kind: 'CONTRACT_REF_PARAM', index: i, type: fn.parameters[i]!.type };
    };
    const inits = fn.locals.flatMap((l, i) => (l.default !== undefined && !isConstant(l.default) ? assignments(b, i, l.type, [], l.default, paramResolver) : []));
    const localInits = b.array(`${base}_local_inits`, 'ContractAssign', inits);

    const resolve: Resolver = (name) => {
        const li = fn.locals.findIndex((l) => l.name === name);
        if (li >= 0) return { kind: 'CONTRACT_REF_LOCAL', index: li, type: fn.locals[li]!.type };
        const port = sup.eventIn.find((p) => p.name === name);
        if (port) return { kind: 'CONTRACT_REF_IN_PORT', index: port.index, type: port.type };
        return undefined;
    };
    const labels = fn.rules.map((r) => r.label);
    const ctx: RuleContext = { b, sup, fn, resolve, labels, schemas, signatures };
    const rules = fn.rules.map((r) => ruleTable(ctx, r));
    const rulesArr = b.array(`${base}_rules`, 'ContractRule', rules);
    return `{"${fn.name}", ${params.count}, ${params.array}, ${params.size}, ${locals.count}, ${locals.array}, ${locals.size}, ${inits.length}, ${localInits}, ${rules.length}, ${rulesArr}}`;
}

interface RuleContext {
    b: TableBuilder;
    sup: Supervisor;
    fn: SupervisionFunction;
    resolve: Resolver;
    labels: string[];
    schemas: Map<string, string>;
    signatures: Map<string, string>;
}

function ruleTable(ctx: RuleContext, rule: Rule): string {
    const base = `${ctx.fn.name}_${rule.label}`;
    const pre = conditionTable(ctx, rule.pre, `${base}_pre`);
    const actions = rule.actions.map((a, i) => actionTable(ctx, a, `${base}_a${i}`));
    const acts = ctx.b.array(`${base}_actions`, 'ContractAction', actions);
    const post = conditionTable(ctx, rule.post, `${base}_post`);
    return `{"${rule.label}", ${pre}, ${actions.length}, ${acts}, ${post}}`;
}

function conditionTable(ctx: RuleContext, cond: Condition, base: string): string {
    const clauses = cond.map((clause, ci) => {
        const events = clause.map((e, ei) => eventTable(ctx, e, `${base}_c${ci}_e${ei}`));
        return `{${events.length}, ${ctx.b.array(`${base}_c${ci}_events`, 'ContractEvent', events)}}`;
    });
    return `{${clauses.length}, ${ctx.b.array(`${base}_clauses`, 'ContractClause', clauses)}}`;
}

function persistence(e: Event): string {
    const p = e.persistence;
    if (p === undefined) return '.persist = CONTRACT_PERSIST_NONE';
    if (p === 'infinite') return '.persist = CONTRACT_PERSIST_INFINITE';
    return `.persist = CONTRACT_PERSIST_TIME, .persist_ns = ${p.ns}`;
}

function eventTable(ctx: RuleContext, e: Event, base: string): string {
    const { b } = ctx;
    switch (e.kind) {
        case 'started':
        case 'endof':
            return `{.kind = ${e.kind === 'started' ? 'CONTRACT_EV_STARTED' : 'CONTRACT_EV_ENDOF'}, .rule = ${ctx.labels.indexOf(e.rule)}, ${persistence(e)}}`;
        case 'duration':
            return `{.kind = CONTRACT_EV_DURATION, .rule = ${ctx.labels.indexOf(e.rule)}, .time_ns = ${e.timeNs}, ${persistence(e)}}`;
        case 'elapsed':
            return `{.kind = CONTRACT_EV_ELAPSED, .time_ns = ${e.timeNs}, ${persistence(e)}}`;
        case 'module': {
            const clauses = e.tests.map((clause, ci) => {
                const tests = clause.map((t) => testTable(ctx, t, `${base}_t${ci}`));
                return `{${tests.length}, ${b.array(`${base}_t${ci}_tests`, 'ContractTest', tests)}}`;
            });
            const testArr = b.array(`${base}_tests`, 'ContractTestClause', clauses);
            const extractions = e.extractions.flatMap((x) => {
                const li = ctx.fn.locals.findIndex((l) => l.name === x.target);
                return li < 0 ? [] : assignments(b, li, ctx.fn.locals[li]!.type, x.path, x.value, ctx.resolve);
            });
            const extr = b.array(`${base}_extractions`, 'ContractAssign', extractions);
            return `{.kind = CONTRACT_EV_MODULE, .module = "${e.source}", .port = ${e.port}, .in_port = ${e.inPort}, .ntest_clauses = ${clauses.length}, .test_clauses = ${testArr}, ${persistence(e)}, .nextractions = ${extractions.length}, .extractions = ${extr}}`;
        }
    }
}

const TEST_OPS = { '==': 'CONTRACT_TEST_EQ', '!=': 'CONTRACT_TEST_NE', '<': 'CONTRACT_TEST_LT', '>': 'CONTRACT_TEST_GT', '<=': 'CONTRACT_TEST_LE', '>=': 'CONTRACT_TEST_GE' } as const;

function testTable(ctx: RuleContext, t: Test, base: string): string {
    const { b } = ctx;
    if (t.op === 'call') {
        const f = b.index.functions.get(t.function);
        if (!f) throw new Error(`unknown function '${t.function}'`);
        const args = f.args.map((a, i) => valueRef(b, t.args[i] ?? { kind: 'struct', elements: [] }, a.type, ctx.resolve));
        return `{CONTRACT_TEST_CALL, {0}, {0}, ${b.userFunction(f)}, ${args.length}, ${b.array(`${base}_args`, 'ContractRef', args)}}`;
    }
    const leftType = valueType(b, t.left, ctx.resolve);
    const rightType = valueType(b, t.right, ctx.resolve, leftType);
    const lt: TypeRef = leftType ?? rightType ?? { primitive: 'int' };
    const rt: TypeRef = rightType ?? lt;
    const fixedLeft = t.left.kind === 'var' ? lt : valueType(b, t.left, ctx.resolve, rt) ?? rt;
    return `{${TEST_OPS[t.op]}, ${valueRef(b, t.left, fixedLeft, ctx.resolve)}, ${valueRef(b, t.right, rt, ctx.resolve)}, NULL, 0, NULL}`;
}

function settingsTable(ctx: RuleContext, module: string, settings: Array<{ port: number; value: Value }>, base: string): string[] {
    const m = ctx.b.index.modules.get(module);
    return settings.flatMap((s) => {
        const port = m?.parameters.find((p) => p.index === s.port);
        if (!port) return [];
        const parts = assignments(ctx.b, 0, port.type, [], s.value, ctx.resolve);
        return [`{${s.port}, ${ctx.b.typeRef(port.type)}, ${parts.length}, ${ctx.b.array(`${base}_p${s.port}`, 'ContractAssign', parts)}, "${port.name}"}`];
    });
}

function signatureOf(ctx: RuleContext, supervisor: string, fnName: string): string {
    const key = `${supervisor}.${fnName}`;
    const known = ctx.signatures.get(key);
    if (known) return known;
    const callee = ctx.b.index.supervisors.get(supervisor)?.functions.find((f) => f.name === fnName);
    if (!callee) throw new Error(`unknown supervision function ${key}`);
    const params = variableBlock(ctx.b, `sig_${supervisor}_${fnName}_params`, callee.parameters);
    const name = ctx.b.unique(`sig_${supervisor}_${fnName}`);
    ctx.b.define(`static const ContractFunctionSignature ${name} = {"${supervisor}", "${fnName}", ${params.count}, ${params.array}, ${params.size}};`);
    ctx.signatures.set(key, `&${name}`);
    return `&${name}`;
}

function actionTable(ctx: RuleContext, a: Action, base: string): string {
    const { b } = ctx;
    switch (a.kind) {
        case 'schema': {
            const schema = b.index.schemas.get(a.schema);
            if (!schema) throw new Error(`unknown schema '${a.schema}'`);
            const ref = schemaTable(b, schema, ctx.schemas);
            const assigns = a.assignments.flatMap((x) => {
                const pi = schema.parameters.findIndex((p) => p.name === x.parameter);
                return pi < 0 ? [] : assignments(b, pi, schema.parameters[pi]!.type, [], x.value, ctx.resolve);
            });
            return `{.kind = CONTRACT_ACT_SCHEMA, .schema = ${ref}, .nassigns = ${assigns.length}, .assigns = ${b.array(`${base}_assigns`, 'ContractAssign', assigns)}}`;
        }
        case 'parameterize': {
            const settings = settingsTable(ctx, a.module, a.settings, base);
            return `{.kind = CONTRACT_ACT_PARAMETERIZE, .module = "${a.module}", .nsettings = ${settings.length}, .settings = ${b.array(`${base}_settings`, 'ContractParamSetting', settings)}}`;
        }
        case 'supervisor': {
            const sig = signatureOf(ctx, a.supervisor, a.function);
            const callee = b.index.supervisors.get(a.supervisor)!.functions.find((f) => f.name === a.function)!;
            const assigns = a.assignments.flatMap((x) => {
                const pi = callee.parameters.findIndex((p) => p.name === x.parameter);
                return pi < 0 ? [] : assignments(b, pi, callee.parameters[pi]!.type, [], x.value, ctx.resolve);
            });
            return `{.kind = CONTRACT_ACT_SUPERVISOR, .callee = ${sig}, .nassigns = ${assigns.length}, .assigns = ${b.array(`${base}_assigns`, 'ContractAssign', assigns)}}`;
        }
        case 'resttime':
        case 'critical':
            return `{.kind = ${a.kind === 'resttime' ? 'CONTRACT_ACT_RESTTIME_MODULE' : 'CONTRACT_ACT_CRITICAL_MODULE'}, .module = "${a.module}"}`;
        case 'compute': {
            const f = b.index.functions.get(a.function);
            if (!f) throw new Error(`unknown function '${a.function}'`);
            const args = f.args.map((arg, i) => valueRef(b, a.args[i] ?? { kind: 'struct', elements: [] }, arg.type, ctx.resolve));
            return `{.kind = CONTRACT_ACT_COMPUTE, .fn = ${b.userFunction(f)}, .nargs = ${args.length}, .args = ${b.array(`${base}_args`, 'ContractRef', args)}}`;
        }
        case 'subscribe':
            return `{.kind = CONTRACT_ACT_SUBSCRIBE, .module = "${a.source}", .src_port = ${a.sourcePort}, .in_port = ${a.inPort}, .mode = ${a.oneShot ? 'CONTRACT_ONESHOT' : 'CONTRACT_CONTINUOUS'}}`;
        case 'notify': {
            const port = ctx.sup.eventOut.find((p) => p.index === a.port);
            const assigns = port ? a.assignments.flatMap((x) => assignments(b, a.port, port.type, x.path, x.value, ctx.resolve)) : [];
            return `{.kind = CONTRACT_ACT_NOTIFY, .out_port = ${a.port}, .nassigns = ${assigns.length}, .assigns = ${b.array(`${base}_assigns`, 'ContractAssign', assigns)}}`;
        }
    }
}
