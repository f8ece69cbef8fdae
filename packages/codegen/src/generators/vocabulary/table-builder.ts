import type { FunctionPrototype, TypeRef, Value } from '../../model/architecture.js';
import type { ArchitectureIndex } from '../../model/lookup.js';
import { cDeclaration, cEnumMember, cInitializer, cTypeName } from '../c/c-syntax.js';
import { typeName } from '../../model/lookup.js';
import { cPointerType } from '../shared-function-header.js';

/**
 * Collects the static C definitions of a vocabulary.c (seam 2, runtime/include/contract/vocabulary.h)
 * in dependency order. Only what is referenced is emitted (no unused static: zero warnings).
 */
export class TableBuilder {
    private readonly definitions: string[] = [];
    private readonly usedTypes = new Set<string>();
    private readonly usedHeaders = new Set<string>();
    private readonly constants = new Map<string, string>();
    private readonly functions = new Map<string, string>();
    private readonly names = new Set<string>();
    private readonly usedEnums = new Set<string>();
    private readonly arrays = new Map<string, string>();
    private readonly arrayDescriptors: { name: string; text: string; element: TypeRef }[] = [];
    private usesBool = false;

    /**
     * `allFieldTables`: every used datatype gets its field table, not only those holding an extension
     * type (the control tools, which are new code, show every value field by field; vocabulary.c
     * keeps the report's tables unchanged).
     */
    constructor(readonly index: ArchitectureIndex, private readonly options: { allFieldTables?: boolean } = {}) {
        // the common/ headers a vocabulary.c includes declare these: table names keep clear of them
        for (const n of userFileScopeNames(index)) this.names.add(n);
    }

    /** Appends a definition (a complete C declaration). */
    define(text: string): void {
        this.definitions.push(text);
    }

    /** A fresh identifier based on `base` (deterministic: numbered in order of creation). */
    unique(base: string): string {
        let name = base;
        for (let n = 2; this.names.has(name); n++) name = `${base}_${n}`;
        this.names.add(name);
        return name;
    }

    /** `&contract_type_X` for a type, recording that its descriptor is needed. */
    typeRef(t: TypeRef): string {
        if ('primitive' in t) {
            if (t.primitive === 'bool') this.usesBool = true;
            return `&contract_type_${t.primitive === 'int' ? 'long' : t.primitive === 'float' ? 'double' : t.primitive}`;
        }
        for (const d of this.index.datatypeClosure(t)) this.usedHeaders.add(d);
        if ('array' in t) return `&${this.arrayDescriptor(t)}`;
        if ('enum' in t) {
            this.usedEnums.add(t.enum);
            return `&contract_type_${t.enum}`;
        }
        this.usedTypes.add(t.datatype);
        return `&contract_type_${t.datatype}`;
    }

    /** The descriptor of an array type (vocabulary.h CONTRACT_ARRAY_TYPE), defined once, element first. */
    private arrayDescriptor(t: { array: TypeRef; size: number }): string {
        const key = JSON.stringify(t);
        const known = this.arrays.get(key);
        if (known) return known;
        const element = this.typeRef(t.array).slice(1);
        const name = this.unique(`contract_array_${typeName(t).replace(/\]\[|\[|\]/g, '_').replace(/_$/, '')}`);
        this.arrayDescriptors.push({ name, text: `static const ContractType ${name} = CONTRACT_ARRAY_TYPE("${typeName(t)}", ${cTypeName(t)}, ${element}, ${t.size}, NULL);`, element: t.array });
        this.arrays.set(key, name);
        return name;
    }

    /** A static constant of type `t` holding `value` (or the type's default), shared when identical. Returns `&name`. */
    constant(t: TypeRef, value: Value | undefined): string {
        const init = cInitializer(this.index, t, value);
        const key = `${JSON.stringify(t)}=${init}`;
        const known = this.constants.get(key);
        if (known) return known;
        if (!('primitive' in t)) this.typeRef(t);
        else if (t.primitive === 'bool') this.usesBool = true;
        const name = this.unique(`k_${this.constants.size}`);
        const decl = `static const ${cDeclaration(t, name)} = ${init};`;
        this.define(decl);
        this.constants.set(key, `&${name}`);
        return `&${name}`;
    }

    /** `&fn_<f>`: the ContractUserFunction adapter of a user function. */
    userFunction(f: FunctionPrototype): string {
        let adapter = this.functions.get(f.name);
        if (!adapter) {
            this.usedHeaders.add(`Function${f.name}`);
            const types = f.args.map((a) => this.typeRef(a.type));
            const argTypes = types.length ? this.unique(`fnargs_${f.name}`) : 'NULL';
            if (types.length) this.define(`static const ContractType *const ${argTypes}[] = {${types.join(', ')}};`);
            const call = `${f.name}(${f.args.map((a, i) => `(${cPointerType(a.type)})a[${i}]`).join(', ')})`;
            const body = f.returns === 'bool' ? `return ${call};` : `${call}; return 0;`;
            const caller = this.unique(`call_${f.name}`);
            this.define(`static int ${caller}(void **a) { ${f.args.length ? '' : '(void)a; '}${body} }`);
            adapter = this.unique(`fn_${f.name}`);
            this.define(`static const ContractUserFunction ${adapter} = {"${f.name}", ${f.returns === 'bool' ? 1 : 0}, ${f.args.length}, ${argTypes}, ${caller}};`);
            this.functions.set(f.name, adapter);
        }
        return `&${adapter}`;
    }

    /** Defines `static const <ctype> <name>[] = {...};` and returns the name, or NULL for no items. */
    array(base: string, ctype: string, items: string[]): string {
        if (items.length === 0) return 'NULL';
        const name = this.unique(base);
        this.define(`static const ${ctype} ${name}[] = {\n    ${items.join(',\n    ')}};`);
        return name;
    }

    /**
     * Field tables (vocabulary.h CONTRACT_DEFINE_TYPE_FIELDS) of the used datatypes that hold a bool, an
     * enumeration or an array, directly or in a nested datatype: the trace then shows their values
     * (`{ranges=[5,5,...],blocked=true}`). Datatypes of report types only keep CONTRACT_DEFINE_TYPE
     * (the report's tutorial generates the same bytes). Their field types become used descriptors.
     */
    private fieldTables(): Map<string, string> {
        const tables = new Map<string, string>();
        for (let added = true; added;) {
            added = false;
            for (const d of this.index.architecture.datatypes) {
                if (!this.usedTypes.has(d.name) || tables.has(d.name)) continue;
                if (!this.options.allFieldTables && !this.holdsExtension({ datatype: d.name })) continue;
                const fields = d.fields.map((f) => `{"${f.name}", offsetof(${d.name}, ${f.name}), ${this.typeRef(f.type)}}`);
                tables.set(d.name, `static const ContractField contract_fields_${d.name}[] = {\n    ${fields.join(',\n    ')}};`);
                added = true;
            }
        }
        return tables;
    }

    private holdsExtension(t: TypeRef): boolean {
        if ('primitive' in t) return t.primitive === 'bool';
        if ('array' in t || 'enum' in t) return true;
        return this.index.datatype(t.datatype).fields.some((f) => this.holdsExtension(f.type));
    }

    /** The datatype and array descriptors, each after those it refers to (field and element types). */
    private descriptorsInOrder(fieldTables: Map<string, string>): string[] {
        const out: string[] = [];
        const done = new Set<string>();
        const arrays = new Map(this.arrayDescriptors.map((a) => [a.name, a]));
        const visit = (t: TypeRef): void => {
            if ('primitive' in t || 'enum' in t) return;
            if ('array' in t) {
                const name = this.arrays.get(JSON.stringify(t));
                const a = name ? arrays.get(name) : undefined;
                if (!a || done.has(a.name)) return;
                done.add(a.name);
                visit(a.element);
                out.push(a.text);
                return;
            }
            const d = this.index.datatype(t.datatype);
            if (!this.usedTypes.has(d.name) || done.has(d.name)) return;
            done.add(d.name);
            const table = fieldTables.get(d.name);
            if (table) for (const f of d.fields) visit(f.type);
            const init = `static const ${d.name} contract_default_${d.name} = ${cInitializer(this.index, { datatype: d.name })};`;
            out.push(table
                ? `${init}\n${table}\nCONTRACT_DEFINE_TYPE_FIELDS(${d.name}, &contract_default_${d.name}, ${d.fields.length}, contract_fields_${d.name})`
                : `${init}\nCONTRACT_DEFINE_TYPE(${d.name}, &contract_default_${d.name})`);
        };
        for (const d of this.index.architecture.datatypes) visit({ datatype: d.name });
        for (const a of this.arrayDescriptors) if (!done.has(a.name)) {
            done.add(a.name);
            visit(a.element);
            out.push(a.text);
        }
        return out;
    }

    /** Includes and type descriptors, then the collected definitions. */
    render(header: string[]): string {
        const fieldTables = this.fieldTables();
        // descriptors only for used types; dependency order from the headers set keeps includes valid
        const headers = [...(this.usesBool ? ['<stdbool.h>'] : []), ...[...this.usedHeaders].sort().map((h) => `"Shared${h}.h"`)].map((h) => `#include ${h}`);
        // enumerations (no dependencies), then datatypes and arrays, each after the descriptors it refers to
        const enums = (this.index.architecture.enums ?? [])
            .filter((e) => this.usedEnums.has(e.name))
            .map((e) => `static const ContractEnumMember contract_members_${e.name}[] = {${e.members.map((m) => `{"${m}", ${cEnumMember(e.name, m)}}`).join(', ')}};\nstatic const ContractType contract_type_${e.name} = CONTRACT_ENUM_TYPE(${e.name}, contract_members_${e.name}, ${e.members.length}, NULL);`);
        const descriptors = this.descriptorsInOrder(fieldTables);
        return [...header, ...headers, '', ...enums, ...descriptors, '', ...this.definitions, ''].join('\n');
    }
}

/** Functions of common/Shared<T>.h (shared-type-header.ts) and of CONTRACT_DEFINE_TYPE (contract/vocabulary.h). */
const TYPE_FUNCTIONS = ['serialize', 'deserialize', 'diff', 'eq', 'inf', 'sup', 'infeq', 'supeq', 'set', 'get', 'print'];

/**
 * File-scope names of the user's datatypes and functions and of what their headers declare:
 * `check` keeps them from the C library's (docs/language-reference.md, "Reserved names"), the
 * tables of vocabulary.c keep clear of them here (a supervision function `get` next to a datatype
 * `params` would otherwise define a table `get_params`, the datatype's parser).
 */
function userFileScopeNames(index: ArchitectureIndex): string[] {
    const { datatypes, functions, enums = [] } = index.architecture;
    return [
        ...[...datatypes, ...enums].flatMap((d) => [d.name, ...TYPE_FUNCTIONS.map((f) => `${f}_${d.name}`)]),
        ...enums.flatMap((e) => e.members.map((m) => cEnumMember(e.name, m))),
        ...functions.map((f) => f.name)
    ];
}
