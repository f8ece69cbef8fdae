/** docs/language-reference.md §2: datatypes, function prototypes, values in declarations, test/compute function use. */
import { GrammarUtils, type AstNode, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    isDataType, isFunctionPrototype, isLocalVariable, isParameter, isPort, isVariableRef,
    type FunctionParameter, type LocalVariable, type Parameter, type Port, type SchemaParameter,
    type ArrayDimension, type Constant, type EnumType, type IndexSegment, type VariableRef,
    type CactalAstType, type Compute, type DataType, type FunctionPrototype, type FunctionTest,
    type TypeRef, type Value
} from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { portKind } from '../model/ports.js';
import { cLayout, segmentIndex, typeName, typeOf, typeOfPathPrefix, typeRefText, variableRefText } from '../model/types.js';
import { constantChain, constantInt } from '../model/constants.js';
import { unknownEscapeMessage, unknownEscapes } from '../model/strings.js';
import { TypeCodes } from './codes/types.js';
import { ProjectNames } from './project-index.js';
import { report } from './report.js';
import { checkValue, writtenInt } from './value-checker.js';
import { C_INT_MAX } from '../model/numbers.js';

type Declaration = { $type: string; name: string; type: TypeRef; value?: Value };

export function typeChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const names = new ProjectNames(services);
    const checkDeclaration = (decl: Declaration, accept: ValidationAcceptor) => {
        if (!decl.value) return;
        checkValue(decl.value, typeOf(decl.type), accept, {
            // locals are initialised from constants and the function's parameters
            allowVariables: isLocalVariable(decl as never),
            what: `'${decl.name}'`
        });
    };
    return {
        DataType: [
            (dt, accept) => checkUniqueTopLevel(names, dt, 'DataType', 'datatype', accept),
            (dt, accept) => checkUniqueTypeOrConstant(names, dt, accept),
            (dt, accept) => checkDuplicateMembers(dt.fields, 'field', dt.name, accept),
            checkRecursiveDatatype
        ],
        FunctionPrototype: [
            (fn, accept) => checkUniqueTopLevel(names, fn, 'FunctionPrototype', 'function', accept),
            (fn, accept) => checkDuplicateMembers(fn.args, 'argument', fn.name, accept)
        ],
        EnumType: [
            (e, accept) => checkUniqueTypeOrConstant(names, e, accept),
            (e, accept) => checkDuplicateMembers(e.members, 'member', e.name, accept),
            checkEnumNotEmpty
        ],
        Constant: [
            (c, accept) => checkUniqueTypeOrConstant(names, c, accept),
            checkConstantCycle,
            (c, accept) => {
                if (c.value && !constantChain(c).cycle) checkValue(c.value, typeOf(c.type), accept, { allowVariables: false, what: `constant '${c.name}'` });
            }
        ],
        ArrayDimension: checkArrayDimension,
        IndexSegment: checkIndexSegment,
        TypeRef: checkTypeRef,
        Field: checkDeclaration,
        Parameter: [checkDeclaration, checkValueSize],
        Port: [checkDeclaration, checkValueSize],
        SchemaParameter: [checkDeclaration, checkValueSize],
        FunctionParameter: [checkDeclaration, checkValueSize],
        LocalVariable: [checkDeclaration, checkValueSize],
        FunctionTest: (test, accept) => checkFunctionUse(test, 'bool', accept),
        Compute: (compute, accept) => checkFunctionUse(compute, 'void', accept),
        StringLiteral: (literal, accept) => checkStringEscapes(literal, 'value', accept),
        Import: (imp, accept) => checkStringEscapes(imp, 'path', accept)
    };
}

/** A warning on each unknown escape of a string literal (model/strings.ts), on the escape itself. */
function checkStringEscapes(node: AstNode, property: string, accept: ValidationAcceptor): void {
    const cst = node.$cstNode && GrammarUtils.findNodeForProperty(node.$cstNode, property);
    if (!cst) return;
    const { line, character } = cst.range.start; // a string is on one line
    for (const e of unknownEscapes(cst.text.slice(1, -1))) {
        const at = character + 1 + e.offset;
        report(accept, TypeCodes['value-string-unknown-escape'], unknownEscapeMessage(e.char),
            { node, range: { start: { line, character: at }, end: { line, character: at + 2 } } });
    }
}

function checkUniqueTopLevel(names: ProjectNames, node: DataType | FunctionPrototype, type: string, word: string, accept: ValidationAcceptor): void {
    if (!node.name) return;
    const same = names.byName([type], node).get(node.name);
    if (same.length <= 1) return;
    const where = names.otherLocations(node, same.map((d) => d.documentUri));
    report(accept, TypeCodes['type-duplicate-name'],
        `${word === 'datatype' ? 'Datatype' : 'Function'} '${node.name}' is defined more than once in the project (also in ${where}); ${word} names are unique across the project.`,
        { node, property: 'name' });
}

/** At most one request (16384 bytes) for events and parameters, 65536 bytes for any other value (runtime limits, docs/runtime-api.md). */
export const MAX_REQUEST_BYTES = 16384;
export const MAX_VALUE_BYTES = 65536;

function checkValueSize(decl: Parameter | Port | SchemaParameter | FunctionParameter | LocalVariable, accept: ValidationAcceptor): void {
    const layout = cLayout(typeOf(decl.type));
    if (!layout) return;
    const small = isParameter(decl) || (isPort(decl) && portKind(decl) === 'event');
    const limit = small ? MAX_REQUEST_BYTES : MAX_VALUE_BYTES;
    if (layout.size <= limit) return;
    const what = isParameter(decl) ? 'a module parameter' : isPort(decl) ? `${portKind(decl) === 'event' ? 'an event' : 'a data'} port` : 'a variable';
    report(accept, TypeCodes['type-too-large'],
        `'${decl.name}' takes ${layout.size} bytes (${typeRefText(decl.type)}); ${what} holds at most ${limit} bytes: use smaller arrays.`,
        { node: decl, property: 'type' });
}

/** Datatypes, enumerations and constants share one namespace (Cactal types and values, C file-scope names). */
function checkUniqueTypeOrConstant(names: ProjectNames, node: DataType | EnumType | Constant, accept: ValidationAcceptor): void {
    if (!node.name) return;
    const same = names.byName(['DataType', 'EnumType', 'Constant'], node).get(node.name);
    const others = same.filter((d) => d.type !== node.$type);
    if (others.length === 0 && (isDataType(node) || same.length <= 1)) return;
    const where = names.otherLocations(node, same.map((d) => d.documentUri));
    const word = (t: string) => t === 'DataType' ? 'datatype' : t === 'EnumType' ? 'enumeration' : 'constant';
    report(accept, TypeCodes['type-duplicate-name'],
        `'${node.name}' is defined more than once in the project (${[...new Set(same.map((d) => word(d.type)))].join(' and ')}; also in ${where}); datatype, enumeration and constant names are unique across the project.`,
        { node, property: 'name' });
}

function checkEnumNotEmpty(e: EnumType, accept: ValidationAcceptor): void {
    if (e.members.length === 0) {
        report(accept, TypeCodes['enum-empty'], `Enumeration '${e.name}' has no members: list at least one (the first is its default value), e.g. enum ${e.name} {IDLE, ACTIVE}.`, { node: e, property: 'name' });
    }
}

function checkConstantCycle(c: Constant, accept: ValidationAcceptor): void {
    const { chain, cycle } = constantChain(c);
    if (cycle && chain[chain.length - 1] === c) {
        report(accept, TypeCodes['const-cycle'],
            `Constant '${c.name}' is defined by itself: ${chain.map((k) => k.name).join(' -> ')}. Give one of them a literal value.`,
            { node: c, property: 'value' });
    }
}

function checkArrayDimension(dim: ArrayDimension, accept: ValidationAcceptor): void {
    if (dim.constant) {
        const constant = dim.constant.ref;
        if (!constant) return; // unresolved: reported by linking
        if (constant.type?.primitive !== 'int' || constant.type.dimensions.length > 0) {
            report(accept, TypeCodes['array-size-invalid'], `An array size is an int: '${constant.name}' is a constant of type ${typeRefText(constant.type)}.`, { node: dim });
            return;
        }
        const n = constantInt(constant);
        if (n !== undefined && n < 1) {
            report(accept, TypeCodes['array-size-invalid'], `An array has at least one element: '${constant.name}' is ${n}.`, { node: dim });
        } else if (n !== undefined && n > C_INT_MAX) {
            report(accept, TypeCodes['number-out-of-range'],
                `Array size '${constant.name}' is too large: an array size is a C int in the generated C, at most ${C_INT_MAX}.`, { node: dim });
        }
        return;
    }
    if (dim.size !== undefined && dim.size < 1) {
        report(accept, TypeCodes['array-size-invalid'], `An array has at least one element: its size is a positive integer, found ${dim.size}.`, { node: dim });
    } else if (dim.size !== undefined && dim.size > C_INT_MAX) {
        report(accept, TypeCodes['number-out-of-range'],
            `Array size ${writtenInt(dim, 'size')} is too large: an array size is a C int in the generated C, at most ${C_INT_MAX}.`, { node: dim, property: 'size' });
    }
}

function checkIndexSegment(segment: IndexSegment, accept: ValidationAcceptor): void {
    const ref = segment.$container;
    if (!isVariableRef(ref)) return;
    const position = ref.path.indexOf(segment);
    const type = typeOfPathPrefix(ref, position);
    if (type.kind === 'unknown') return;
    const prefix = variableRefText({ ...ref, path: ref.path.slice(0, position) } as VariableRef);
    if (type.kind !== 'array') {
        report(accept, TypeCodes['array-index-invalid'], `'${prefix}' is a ${typeName(type)}, not an array: only arrays have elements [i].`, { node: segment });
        return;
    }
    if (segment.constant) {
        const constant = segment.constant.ref;
        if (!constant) return;
        if (constant.type?.primitive !== 'int' || constant.type.dimensions.length > 0) {
            report(accept, TypeCodes['array-index-invalid'], `An index is an int: '${constant.name}' is a constant of type ${typeRefText(constant.type)}.`, { node: segment });
            return;
        }
    }
    const i = segmentIndex(segment);
    if (i !== undefined && (i < 0 || i >= type.size)) {
        report(accept, TypeCodes['array-index-invalid'],
            `Index ${i} is out of range: '${prefix}' is a ${typeName(type)}, its elements are [0] to [${type.size - 1}].`, { node: segment });
    }
}

export function checkDuplicateMembers(members: Array<{ name: string; $type: string } & object>, word: string, owner: string, accept: ValidationAcceptor): void {
    const seen = new Set<string>();
    for (const m of members) {
        if (!m.name) continue;
        if (seen.has(m.name)) {
            report(accept, TypeCodes['type-duplicate-member'], `Duplicate ${word} '${m.name}' in ${owner}: each ${word} needs its own name.`, { node: m as never, property: 'name' });
        }
        seen.add(m.name);
    }
}

function checkRecursiveDatatype(dt: DataType, accept: ValidationAcceptor): void {
    const path: DataType[] = [];
    const visiting = new Set<DataType>();
    const done = new Set<DataType>();
    const dfs = (current: DataType): DataType[] | undefined => {
        if (current === dt && path.length > 0) return [...path, current];
        if (visiting.has(current) || done.has(current)) return undefined;
        visiting.add(current);
        path.push(current);
        for (const field of current.fields) {
            let t = typeOf(field.type);
            while (t.kind === 'array') t = t.element;
            if (t.kind === 'struct') {
                const found = dfs(t.datatype);
                if (found) return found;
            }
        }
        path.pop();
        visiting.delete(current);
        done.add(current);
        return undefined;
    };
    const cycle = dfs(dt);
    if (cycle) {
        report(accept, TypeCodes['type-recursive'],
            `Datatype '${dt.name}' contains itself: ${cycle.map((d) => d.name).join(' -> ')}. A datatype cannot contain itself, directly or through other datatypes.`,
            { node: dt, property: 'name' });
    }
}

function checkTypeRef(ref: TypeRef, accept: ValidationAcceptor): void {
    const container = ref.$container;
    if (isFunctionPrototype(container) && ref.$containerProperty === 'returnType') {
        if ((ref.primitive !== 'bool' && ref.primitive !== 'void') || ref.dimensions.length > 0) {
            report(accept, TypeCodes['type-function-return'],
                `Function '${container.name}' returns ${typeRefText(ref)}: a function returns bool (a test function, used in event tests) or void (a compute function, used by compute).`,
                { node: ref });
        }
        return;
    }
    if (ref.primitive === 'void') {
        report(accept, TypeCodes['type-primitive-misuse'],
            `void is only a function return type; use int, float, string, bool, a datatype, an enumeration or an array of these here.`, { node: ref });
    }
}

function checkFunctionUse(node: FunctionTest | Compute, expected: 'bool' | 'void', accept: ValidationAcceptor): void {
    const fn = node.function?.ref;
    if (!fn) return;
    const returns = fn.returnType?.primitive;
    if (returns !== expected && (returns === 'bool' || returns === 'void')) {
        const message = expected === 'bool'
            ? `'${fn.name}' is a compute function (returns void): only bool test functions can be used in an event test; call it with compute in the actions.`
            : `'${fn.name}' is a test function (returns bool): compute calls void functions; use it in an event test <...> instead.`;
        report(accept, TypeCodes['type-function-misuse'], message, { node, property: 'function' });
    }
    if (fn.args.length !== node.args.length) {
        report(accept, TypeCodes['value-type-mismatch'],
            `'${fn.name}' takes ${fn.args.length} argument${fn.args.length === 1 ? '' : 's'} (${fn.args.map((a) => `${typeRefText(a.type)} ${a.name}`).join(', ')}); ${node.args.length} given.`,
            { node, property: 'function' });
    }
    const n = Math.min(fn.args.length, node.args.length);
    for (let i = 0; i < n; i++) {
        checkValue(node.args[i]!, typeOf(fn.args[i]!.type), accept, { allowVariables: true, what: `argument '${fn.args[i]!.name}' of ${fn.name}` });
    }
}
