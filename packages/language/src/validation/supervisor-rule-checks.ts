/**
 * docs/language-reference.md §6, rules and conditions: rules never use the function's parameters; ORD events and
 * `ord_schema`; test operands of the same type; extraction targets are locals and values fit them;
 * the report's rule hygiene warnings (§4.7): endof(L) in L's postcondition, started/duration(L) in
 * L's precondition, clauses with more than one transient event, module events never subscribed; a
 * rule that only a transient `elapsed` ends, made active again by a rule sequence (elapsed-once).
 */
import { AstUtils, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isDurationEvent, isElapsedEvent, isEndofEvent, isExtraction, isFunctionParameter, isLocalVariable, isModuleEvent, isModuleInstance,
    isNotify, isRule, isStartedEvent, isStructValue, isSupervisionFunction, isVariableRef,
    isIntLiteral, isRealLiteral, isStringLiteral, isBoolLiteral, isRelationalTest, isClause,
    type CactalAstType, type Clause, type ElapsedEvent, type EqualityTest, type Event, type Extraction, type ModuleEvent, type RelationalTest,
    type Port, type Rule, type TestOperand, type VariableRef
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { isNumeric, isOrdered, sameType, typeName, typeOfVariableRef, variableRefText, type CactalType } from '../model/types.js';
import { SupervisorCodes } from './codes/supervisors.js';
import { deliveredPorts, eventInPort, inputPortRead, subscribesOf } from '../model/event-in-port.js';
import { activationsBounded } from '../model/rule-activity.js';
import { ordSchemaTestName } from '../model/ord-schema-tests.js';
import { ProjectNames } from './project-index.js';
import { nearName } from './unresolved-messages.js';
import { report } from './report.js';
import { checkNumberRange, checkValue } from './value-checker.js';

/** The ORD event ports (docs/semantics.md "Scheduler: critical delay (ORD:0)", "Scheduler: conflict (ORD:1)"): 0 = critical delay missed, 1 = activation refused. */
export const ORD_EVENT_PORTS: Readonly<Record<number, string>> = { 0: 'critical delay missed', 1: 'schema activation refused' };

export function supervisorRuleChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const names = new ProjectNames(services);
    return {
        VariableRef: [checkNoParameterInRule, checkOrdSchemaUse],
        ModuleEvent: [checkOrdPort, checkEventSubscribed, checkEventVariables],
        EqualityTest: [checkTestOperands, (test, accept) => checkOrdSchemaName(test, names, accept)],
        RelationalTest: checkTestOperands,
        Extraction: checkExtraction,
        Rule: [checkOwnRuleEvents, checkElapsedOnce],
        Clause: checkTransientEvents
    };
}

function checkNoParameterInRule(ref: VariableRef, accept: ValidationAcceptor): void {
    const variable = ref.variable?.ref;
    if (!isFunctionParameter(variable) || !AstUtils.getContainerOfType(ref, isRule)) return;
    const fn = AstUtils.getContainerOfType(ref, isSupervisionFunction);
    const local = fn?.locals.flatMap((b) => b.variables).find((l) => isVariableRef(l.value) && l.value.variable?.ref === variable && l.value.path.length === 0);
    report(accept, SupervisorCodes['supervisor-rule-uses-parameter'],
        `Rules cannot use the parameter '${variable.name}' of ${fn?.name ?? 'the function'}: they use locals, event-port variables and constants. ${local ? `Use the local '${local.name}', initialised from it.` : `Copy it into a local (local { ${variable.type?.primitive ?? variable.type?.datatype?.$refText ?? 'T'} ${variable.name}_ = ${variable.name}; }) and use that.`}`,
        { node: ref, property: 'variable', data: local ? { local: local.name } : {} });
}

function checkOrdSchemaUse(ref: VariableRef, accept: ValidationAcceptor): void {
    if (!ref.ordSchema) return;
    // Declarations (defaults) report value-not-constant; here: rules, locals and schema parameterisations.
    if (!AstUtils.getContainerOfType(ref, (n) => isRule(n) || isLocalVariable(n) || isModuleInstance(n))) return;
    const event = AstUtils.getContainerOfType(ref, isModuleEvent);
    const extraction = AstUtils.getContainerOfType(ref, isExtraction);
    const isTarget = extraction !== undefined && extraction.target === ref;
    if (event?.ord && !isTarget) return;
    report(accept, SupervisorCodes['supervisor-ord-schema-misuse'],
        isTarget
            ? `'ord_schema' is read-only: it holds the schema name of an ORD event; extract it into a local (local = ord_schema).`
            : `'ord_schema' holds the schema name of an ORD event: it is only usable in the tests and extractions of an ORD:0/ORD:1 event (e.g. ORD:0<ord_schema == "schemaCommande1">).`,
        { node: ref });
}

function checkOrdSchemaName(test: EqualityTest, names: ProjectNames, accept: ValidationAcceptor): void {
    const literal = ordSchemaTestName(test);
    if (!literal || names.byName(['Schema'], test).has(literal.value)) return;
    const event = AstUtils.getContainerOfType(test, isModuleEvent);
    const what = event?.ordPort === 1 ? 'whose activation was refused' : 'whose cycle missed its critical delay';
    report(accept, SupervisorCodes['supervisor-ord-schema-unknown'],
        `No schema is named "${literal.value}": ORD:${event?.ordPort ?? 0} names the schema ${what}, so this test is ${test.operator === '==' ? 'never' : 'always'} true.${nearName(literal.value, names.byName(['Schema'], test).keys())}`,
        { node: literal });
}

function checkOrdPort(event: ModuleEvent, accept: ValidationAcceptor): void {
    if (!event.ord || event.ordPort === undefined) return;
    if (!(event.ordPort in ORD_EVENT_PORTS)) {
        report(accept, SupervisorCodes['supervisor-ord-port'],
            `ORD has no event port ${event.ordPort}: its events are ORD:0 (${ORD_EVENT_PORTS[0]}) and ORD:1 (${ORD_EVENT_PORTS[1]}).`,
            { node: event, property: 'ordPort' });
    }
}

function checkEventSubscribed(event: ModuleEvent, accept: ValidationAcceptor): void {
    if (event.ord) return;
    const source = event.source?.ref;
    const port = event.port?.ref;
    const fn = AstUtils.getContainerOfType(event, isSupervisionFunction);
    if (!source || !port || !fn || subscribesOf(event).length > 0) return;
    report(accept, SupervisorCodes['supervisor-event-not-subscribed'],
        `Function ${fn.name} never subscribes to ${source.name}:${port.index}, so this event never occurs and its clause stays false: add 'subscribe ${source.name}:${port.index} =* :<input port>' to a rule that is active before.`,
        { node: event, property: 'port' });
}

function checkEventVariables(event: ModuleEvent, accept: ValidationAcceptor): void {
    if (event.ord || !event.source?.ref || !event.port?.ref) return;
    const binding = eventInPort(event);
    const own = binding.delivered;
    if (own.length === 0) return; // never subscribed: reported by supervisor-event-not-subscribed
    const name = `${event.source.ref.name}:${event.port.ref.index}`;
    const list = (ports: Port[]) => ports.map((p) => `:${p.index} ${p.name}`).join(', ');
    for (const clause of event.tests) {
        for (const node of AstUtils.streamAllContents(clause)) {
            const port = isVariableRef(node) ? inputPortRead(node) : undefined;
            if (port && !own.includes(port)) {
                report(accept, SupervisorCodes['supervisor-event-variable'],
                    `${name} is delivered to ${list(own)}; '${variableRefText(node as VariableRef)}' is the variable of input port :${port.index}, which this event does not write: the test would read an older value.`,
                    { node });
            }
        }
    }
    if (binding.ambiguous) {
        const alternatives = binding.read.map((p) => `${name}<${p.name} ...>`).join(' or ');
        report(accept, SupervisorCodes['supervisor-event-variable'],
            `${name} is delivered to ${list(own)} (one subscribe each), and this event reads the variables of ${list(binding.read)}: an occurrence comes in on one of them and writes that one only, so what it reads of the others is older. Read one input port per event; to wait for either, write one event per port: ${alternatives}.`,
            { node: event, property: 'port' });
    }
    if (event.extractions.length === 0) return;
    const clauseEvents = isClause(event.$container) ? event.$container.events.filter(isModuleEvent) : [event];
    const written = new Set(clauseEvents.flatMap(deliveredPorts));
    for (const extraction of event.extractions) {
        if (!extraction.value) continue;
        for (const node of [extraction.value, ...AstUtils.streamAllContents(extraction.value)]) {
            const port = isVariableRef(node) ? inputPortRead(node) : undefined;
            if (port && !written.has(port)) {
                report(accept, SupervisorCodes['supervisor-event-variable'],
                    `No module event of this clause writes input port :${port.index} ('${port.name}'); ${name} is delivered to ${list(own)}: the extraction would read an older value.`,
                    { node });
            }
        }
    }
}

/** The type of a test operand, or undefined for a structured value (its type comes from the other side). */
function operandType(op: TestOperand): CactalType | undefined {
    if (isIntLiteral(op)) return { kind: 'primitive', name: 'int' };
    if (isRealLiteral(op)) return { kind: 'primitive', name: 'float' };
    if (isStringLiteral(op)) return { kind: 'primitive', name: 'string' };
    if (isBoolLiteral(op)) return { kind: 'primitive', name: 'bool' };
    if (isVariableRef(op)) return typeOfVariableRef(op);
    return undefined;
}

function operandText(op: TestOperand): string {
    if (isVariableRef(op)) return `'${variableRefText(op)}'`;
    if (isStringLiteral(op)) return `the string ${JSON.stringify(op.value)}`;
    if (isBoolLiteral(op)) return `the bool ${op.value ? 'true' : 'false'}`;
    return `the ${isIntLiteral(op) ? 'integer' : 'real'} ${op.$cstNode?.text ?? (op as { value?: unknown }).value}`;
}

function checkTestOperands(test: EqualityTest | RelationalTest, accept: ValidationAcceptor): void {
    if (!test.left || !test.right) return;
    const left = operandType(test.left);
    const right = operandType(test.right);
    // a number compared is one of the C of the test: an integer is a long, or a double beside a float
    const isFloat = (t: CactalType | undefined) => t?.kind === 'primitive' && t.name === 'float';
    checkNumberRange(test.left, isFloat(left) || isFloat(right) ? 'float' : 'int', accept, 'this comparison');
    checkNumberRange(test.right, isFloat(left) || isFloat(right) ? 'float' : 'int', accept, 'this comparison');
    if (!left || !right) {
        // a structured value takes the type of the other operand
        const [value, other] = !left ? [test.left, right] : [test.right, left];
        if (other && isStructValue(value)) checkValue(value, other, accept, { allowVariables: true, what: 'this comparison' });
        return;
    }
    if (isRelationalTest(test) && (!isOrdered(left) || !isOrdered(right))) {
        const unordered = !isOrdered(left) ? left : right;
        report(accept, SupervisorCodes['supervisor-test-type'],
            `Cannot order values of type ${typeName(unordered)} with ${test.operator}: ${unordered.kind === 'array' ? 'compare one element (ranges[90]) or test the whole array with == / !=' : 'a bool is tested with == or !='}.`,
            { node: test, property: 'operator' });
        return;
    }
    if (sameType(left, right) || (isNumeric(left) && isNumeric(right))) return;
    report(accept, SupervisorCodes['supervisor-test-type'],
        `Cannot compare ${operandText(test.left)} (${typeName(left)}) with ${operandText(test.right)} (${typeName(right)}): both operands of a test have the same type (int and float mix).`,
        { node: test, property: 'operator' });
}

function checkExtraction(extraction: Extraction, accept: ValidationAcceptor): void {
    const target = extraction.target;
    if (!target) return;
    if (isModuleEvent(extraction.$container)) {
        const variable = target.variable?.ref;
        // a parameter is reported by supervisor-rule-uses-parameter
        if (variable && !isLocalVariable(variable) && !isFunctionParameter(variable)) {
            report(accept, SupervisorCodes['supervisor-extraction-target'],
                `An extraction assigns a local of the function (or one of its fields): '${variableRefText(target)}' is an event-port variable, written by events. Extract into a local instead.`,
                { node: target });
            return;
        }
    }
    if (isNotify(extraction.$container)) {
        const port = extraction.$container.port?.ref;
        const variable = target.variable?.ref;
        if (port && variable && variable !== port && !isFunctionParameter(variable)) {
            report(accept, SupervisorCodes['supervisor-notify-target'],
                `notify :${port.index} assigns the variable of that port, '${port.name}' (or its fields), not '${variableRefText(target)}'.`,
                { node: target });
            return;
        }
    }
    if (target.ordSchema || !extraction.value) return;
    const type = typeOfVariableRef(target);
    checkValue(extraction.value, type, accept, { allowVariables: true, what: `'${variableRefText(target)}'` });
}

function checkOwnRuleEvents(rule: Rule, accept: ValidationAcceptor): void {
    for (const event of eventsOf(rule.postcondition?.clauses ?? [])) {
        if (isEndofEvent(event) && event.rule?.ref === rule) {
            report(accept, SupervisorCodes['supervisor-endof-own-postcondition'],
                `endof(${rule.name}) in the postcondition of ${rule.name} can never be true: the postcondition defines when ${rule.name} becomes inactive, it cannot wait for an event that follows that deactivation (report §4.7).`,
                { node: event });
        }
    }
    for (const event of eventsOf(rule.precondition?.clauses ?? [])) {
        if ((isStartedEvent(event) || isDurationEvent(event)) && event.rule?.ref === rule) {
            const word = isStartedEvent(event) ? 'started' : 'duration';
            report(accept, SupervisorCodes['supervisor-started-own-precondition'],
                `${word}(${rule.name}) in the precondition of ${rule.name} can never be true: the precondition defines when ${rule.name} becomes active, it cannot wait for an event that follows that activation (report §4.7).`,
                { node: event });
        }
    }
}

/** A transient `elapsed=t`: present at one instant of the function's run. */
const onceEvent = (e: Event): e is ElapsedEvent => isElapsedEvent(e) && !e.persistence;

/**
 * A rule that only `elapsed` ends (each postcondition clause waits for a transient `elapsed=t`)
 * and that may become active again (activationsBounded): after its first activation nothing ends it.
 */
function checkElapsedOnce(rule: Rule, accept: ValidationAcceptor): void {
    const post = rule.postcondition?.clauses ?? [];
    if (post.length === 0 || !post.every((c) => c.events.some(onceEvent)) || activationsBounded(rule)) return;
    const again = (rule.precondition?.clauses ?? []).find((c) => !c.events.some(onceEvent)) ?? rule.precondition?.clauses[0];
    const cause = again?.$cstNode?.text.replace(/\s+/g, ' ') ?? 'its precondition';
    for (const event of post.flatMap((c) => c.events).filter(onceEvent)) {
        const time = event.time?.text ?? '?';
        report(accept, SupervisorCodes['supervisor-elapsed-once'],
            `elapsed=${time} occurs once, ${time} after the function started: ${rule.name} becomes active on ${cause}, which may come again, and a later ${rule.name} (or one that starts after ${time}) is never ended by it. To end ${rule.name} ${time} after each of its activations, write duration(${rule.name})=${time}.`,
            { node: event, data: { suggestion: `duration(${rule.name})=${time}` } });
    }
}

function eventsOf(clauses: Clause[]): Event[] {
    return clauses.flatMap((c) => c.events);
}

function checkTransientEvents(clause: Clause, accept: ValidationAcceptor): void {
    if (clause.events.length < 2) return;
    const transient = clause.events.filter((e) => !e.persistence);
    if (transient.length < 2) return;
    report(accept, SupervisorCodes['supervisor-clause-transient'],
        `${transient.length} events of this clause have no persistence: events are never simultaneous, so the clause can never be true. Give all of them but one a persistence ({1s} or {infinite}); the transient one must be the last notified (report §4.7).`,
        { node: transient[1]! });
}

