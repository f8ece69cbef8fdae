/**
 * docs/language-reference.md §3: module and supervisor names, project-wide uniqueness, block order, synchronous and
 * asynchronous restrictions, port indexes per kind and direction, member names, time literals.
 */
import { type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isDataFlowsBlock, isEventFlowsBlock, isParametersBlock, isSchedulingBlock,
    type CactalAstType, type Module, type ModuleBlock, type Parameter, type Port, type Supervisor, type TimeValue
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { parametersOf, schedulingPropertiesOf } from '../model/blocks.js';
import { portsOf } from '../model/ports.js';
import { parseTime } from '../model/time.js';
import { C_INT_MAX, DURATION_NS_MAX, exactNanoseconds } from '../model/numbers.js';
import { checkBlockOrder, type BlockOrder } from './block-order.js';
import { ModuleCodes } from './codes/modules.js';
import { TypeCodes } from './codes/types.js';
import { ProjectNames } from './project-index.js';
import { report } from './report.js';
import { writtenInt } from './value-checker.js';

const NAME_PATTERN = /^[A-Z]{3}$/;
const BLOCK_ORDER = ['parameters', 'scheduling', 'data flows', 'event flows'] as const;
type BlockName = (typeof BLOCK_ORDER)[number];

function blockName(block: ModuleBlock): BlockName {
    if (isParametersBlock(block)) return 'parameters';
    if (isSchedulingBlock(block)) return 'scheduling';
    if (isDataFlowsBlock(block)) return 'data flows';
    return 'event flows';
}

function blockKeyword(block: ModuleBlock): string {
    return isDataFlowsBlock(block) ? 'data' : isEventFlowsBlock(block) ? 'event' : blockName(block);
}

const MODULE_BLOCKS: BlockOrder<ModuleBlock, BlockName> = {
    order: BLOCK_ORDER, nameOf: blockName, keywordOf: blockKeyword,
    duplicate: ModuleCodes['module-block-duplicate'], outOfOrder: ModuleCodes['module-block-order']
};


/** The largest parameter port index (docs/language-reference.md §3): PARAM_SIZE_IN is indexed by port number. */
export const MAX_PARAMETER_INDEX = 1023;

export function moduleChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const names = new ProjectNames(services);
    const checkName = (node: Module | Supervisor, accept: ValidationAcceptor) => checkModuleName(node, names, accept);
    return {
        Module: [checkName, checkBlocks, checkPorts],
        Supervisor: [checkName, checkPorts],
        TimeValue: checkTime
    };
}

function checkModuleName(node: Module | Supervisor, names: ProjectNames, accept: ValidationAcceptor): void {
    const word = node.$type === 'Module' ? 'Module' : 'Supervisor';
    if (!node.name) return;
    if (node.name === 'ORD') {
        report(accept, ModuleCodes['module-name-reserved'], `ORD is the scheduler's name: choose another three-letter name for this ${word.toLowerCase()}.`, { node, property: 'name' });
        return;
    }
    if (!NAME_PATTERN.test(node.name)) {
        const upper = node.name.toUpperCase();
        const suggestion = NAME_PATTERN.test(upper) && upper !== 'ORD' ? upper : undefined;
        report(accept, ModuleCodes['module-name-format'],
            `${word} name '${node.name}' must be exactly three upper-case letters (A-Z)${suggestion ? `, e.g. '${suggestion}'` : ''}.`,
            { node, property: 'name', data: suggestion ? { suggestion } : {} });
        return;
    }
    const same = names.byName(['Module', 'Supervisor'], node).get(node.name);
    if (same.length > 1) {
        const where = names.otherLocations(node, same.map((d) => d.documentUri));
        report(accept, ModuleCodes['module-name-duplicate'],
            `'${node.name}' names more than one module or supervisor (also in ${where}); names are unique across the project.`,
            { node, property: 'name' });
    }
}

function checkBlocks(module: Module, accept: ValidationAcceptor): void {
    checkBlockOrder(`Module ${module.name}`, module.blocks, MODULE_BLOCKS, accept);
    const scheduling = module.blocks.filter(isSchedulingBlock);
    if (module.kind === 'asynchronous') {
        for (const block of module.blocks) {
            if (isSchedulingBlock(block)) {
                report(accept, ModuleCodes['module-async-forbidden-block'],
                    `Asynchronous module ${module.name} is not scheduled: remove the 'scheduling' block, or declare it 'synchronous module'.`,
                    { node: block, keyword: 'scheduling' });
            } else if (isDataFlowsBlock(block)) {
                report(accept, ModuleCodes['module-async-forbidden-block'],
                    `Asynchronous module ${module.name} has no data ports: use event ports ('event flows') or declare it 'synchronous module'.`,
                    { node: block, keyword: 'data' });
            }
        }
        return;
    }
    if (scheduling.length === 0) {
        report(accept, ModuleCodes['module-scheduling-missing'],
            `Synchronous module ${module.name} needs a 'scheduling { C=<time>; }' block giving its nominal execution time (e.g. C=1ms).`,
            { node: module, property: 'name' });
        return;
    }
    const properties = schedulingPropertiesOf(module);
    let hasC = false;
    for (const p of properties) {
        if (p.name !== 'C') {
            report(accept, ModuleCodes['module-scheduling-property'], `Unknown scheduling property '${p.name}': the only one is C (nominal execution time, e.g. C=1ms).`, { node: p, property: 'name' });
        } else if (hasC) {
            report(accept, ModuleCodes['module-scheduling-property'], `C is given twice in module ${module.name}: keep one.`, { node: p, property: 'name' });
        } else {
            hasC = true;
        }
    }
    if (!hasC) {
        report(accept, ModuleCodes['module-scheduling-missing'],
            `The scheduling block of ${module.name} must give C, the nominal execution time (e.g. C=1ms;).`, { node: scheduling[0]!, keyword: 'scheduling' });
    }
}

/** Port indexes per kind and direction, parameters, member names; synchronous modules: out event ports only. */
function checkPorts(owner: Module | Supervisor, accept: ValidationAcceptor): void {
    const groups = new Map<string, Array<Port | Parameter>>();
    const add = (key: string, node: Port | Parameter) => {
        const list = groups.get(key) ?? [];
        list.push(node);
        groups.set(key, list);
    };
    const params = owner.$type === 'Module' ? parametersOf(owner) : [];
    for (const p of params) add('parameter', p);
    for (const info of portsOf(owner)) add(`${info.direction === 'in' ? 'input' : 'output'} ${info.kind}`, info.port);

    for (const [group, members] of groups) {
        const used = new Set<number>();
        const allIndexes = new Set(members.map((m) => m.index));
        for (const m of members) {
            if (typeof m.index !== 'number' || Number.isNaN(m.index)) continue;
            if (m.index < 0) {
                report(accept, ModuleCodes['port-index-negative'], `Port index ${m.index} is negative: indexes are 0, 1, 2, ...`, { node: m, property: 'index' });
                continue;
            }
            if (m.index > C_INT_MAX) {
                report(accept, TypeCodes['number-out-of-range'],
                    `Port index ${writtenInt(m, 'index')} is too large: a port index is a C int in the generated C and the runtime, at most ${C_INT_MAX}.`, { node: m, property: 'index' });
                continue;
            }
            if (group === 'parameter' && m.index > MAX_PARAMETER_INDEX) {
                report(accept, ModuleCodes['parameter-index-too-large'],
                    `Parameter port index :${m.index} is too large: at most ${MAX_PARAMETER_INDEX}. The generated module.c gives the runtime a table of one size per parameter index up to the largest (PARAM_SIZE_IN), so :${m.index} would make it ${m.index + 1} entries long.`, { node: m, property: 'index' });
                continue;
            }
            if (used.has(m.index)) {
                let free = 0;
                while (allIndexes.has(free)) free++;
                allIndexes.add(free);
                report(accept, ModuleCodes['port-index-duplicate'],
                    `${group === 'parameter' ? 'Parameter' : group[0]!.toUpperCase() + group.slice(1)} port index :${m.index} is already used in ${owner.name}; indexes are unique per kind and direction (free: :${free}).`,
                    { node: m, property: 'index', data: { suggestedIndex: free } });
            }
            used.add(m.index);
        }
    }

    const names = new Set<string>();
    for (const m of [...params, ...portsOf(owner).map((p) => p.port)]) {
        if (!m.name) continue;
        if (names.has(m.name)) {
            report(accept, ModuleCodes['member-name-duplicate'],
                `'${m.name}' is already a parameter or port variable of ${owner.name}: every name in its interface must be unique.`,
                { node: m, property: 'name' });
        }
        names.add(m.name);
    }

    if (owner.$type === 'Module' && owner.kind === 'synchronous') {
        for (const info of portsOf(owner)) {
            if (info.kind === 'event' && info.direction === 'in') {
                report(accept, ModuleCodes['module-sync-event-in'],
                    `Synchronous module ${owner.name} cannot have input event port :${info.index}: it only has 'out' event ports (an asynchronous module reacts to events).`,
                    { node: info.port, property: 'direction' });
            }
        }
    }
}

const UNIT_DECIMALS: Record<string, number> = { ns: 0, us: 3, ms: 6, s: 9 };

/** Whether duration `text` has digits below the nanosecond (`1.5ns`, `0.0001us`), which exactNanoseconds rounds. */
function subNanosecond(text: string): boolean {
    const m = /^-?[0-9]+(?:\.([0-9]+))?(ns|us|ms|s)$/.exec(text.trim());
    return !!m && /[1-9]/.test((m[1] ?? '').slice(UNIT_DECIMALS[m[2]!]));
}

function checkTime(time: TimeValue, accept: ValidationAcceptor): void {
    const parsed = parseTime(time.text ?? '');
    if (parsed && parsed.amount <= 0) {
        report(accept, ModuleCodes['time-not-positive'], `Duration ${time.text} must be greater than zero (e.g. 500us, 1ms, 1s).`, { node: time });
        return;
    }
    const ns = exactNanoseconds(time.text ?? '');
    const rounded = subNanosecond(time.text ?? '');
    if (ns === 0n && rounded) {
        report(accept, ModuleCodes['time-not-positive'], `Duration ${time.text} is less than half a nanosecond: durations are whole nanoseconds, and it rounds to 0ns.`, { node: time });
        return;
    }
    if (ns !== undefined && rounded) {
        report(accept, ModuleCodes['time-rounded'], `Duration ${time.text} is not a whole number of nanoseconds: it is rounded to ${ns}ns (durations are whole nanoseconds in the generated C and the runtime).`, { node: time });
    }
    if (ns !== undefined && ns > BigInt(DURATION_NS_MAX)) {
        report(accept, TypeCodes['number-out-of-range'],
            `Duration ${time.text} is too long: a duration is at most ${DURATION_NS_MAX}ns (about 104 days), which the generated C and the tools hold exactly.`, { node: time });
    }
}
