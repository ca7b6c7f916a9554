//! The typed AST of ST and IL files: POUs with their declarations and ST or IL bodies, type declarations, configurations; every node with its span.

use crate::diag::Span;

/// A name as written, with where (IEC names compare case-insensitively).
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    /// The spelling as written.
    pub name: String,
    /// Where.
    pub span: Span,
}

/// A whole `.st`/`.il` file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StFile {
    /// `PROGRAM`, `FUNCTION_BLOCK` and `FUNCTION` declarations, in order.
    pub pous: Vec<Pou>,
    /// The declarations of every `TYPE … END_TYPE` block, in order.
    pub types: Vec<TypeDecl>,
    /// `CONFIGURATION` declarations.
    pub configurations: Vec<Configuration>,
}

/// What a POU is.
#[derive(Clone, Debug, PartialEq)]
pub enum PouKind {
    /// `PROGRAM`.
    Program,
    /// `FUNCTION_BLOCK`.
    FunctionBlock,
    /// `FUNCTION name : result`.
    Function {
        /// The result type.
        result: TypeRef,
    },
}

/// A program organisation unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Pou {
    /// What it is.
    pub kind: PouKind,
    /// Its name.
    pub name: Ident,
    /// Its variable sections, in order.
    pub vars: Vec<VarBlock>,
    /// Its body.
    pub body: Body,
    /// From the keyword to the end keyword.
    pub span: Span,
}

/// A POU body.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// Structured Text.
    St(Vec<Stmt>),
    /// Instruction List.
    Il(Vec<IlLine>),
}

/// A variable section's class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarClass {
    /// `VAR`.
    Local,
    /// `VAR_INPUT`.
    Input,
    /// `VAR_OUTPUT`.
    Output,
    /// `VAR_IN_OUT`.
    InOut,
    /// `VAR_GLOBAL`.
    Global,
    /// `VAR_EXTERNAL`.
    External,
    /// `VAR_TEMP`.
    Temp,
}

impl VarClass {
    /// Every class with its keyword.
    pub const KEYWORDS: [(VarClass, &'static str); 7] = [
        (VarClass::Local, "VAR"),
        (VarClass::Input, "VAR_INPUT"),
        (VarClass::Output, "VAR_OUTPUT"),
        (VarClass::InOut, "VAR_IN_OUT"),
        (VarClass::Global, "VAR_GLOBAL"),
        (VarClass::External, "VAR_EXTERNAL"),
        (VarClass::Temp, "VAR_TEMP"),
    ];
    /// The keyword that opens a section of this class.
    pub fn keyword(self) -> &'static str {
        VarClass::KEYWORDS.iter().find(|(c, _)| *c == self).map_or("VAR", |(_, k)| k)
    }
}

/// `VAR … END_VAR` and its kin.
#[derive(Clone, Debug, PartialEq)]
pub struct VarBlock {
    /// The class.
    pub class: VarClass,
    /// `CONSTANT`.
    pub constant: bool,
    /// `RETAIN` (`Some(true)`) or `NON_RETAIN` (`Some(false)`).
    pub retain: Option<bool>,
    /// The declarations.
    pub decls: Vec<VarDecl>,
    /// From the keyword to `END_VAR`.
    pub span: Span,
}

/// `a, b AT %IX0.0 : TYPE := init;`
#[derive(Clone, Debug, PartialEq)]
pub struct VarDecl {
    /// The names declared.
    pub names: Vec<Ident>,
    /// `AT %IX0.0`: the address and where.
    pub location: Option<(String, Span)>,
    /// The type.
    pub ty: TypeRef,
    /// The initial value.
    pub init: Option<Init>,
    /// From the first name to the `;`.
    pub span: Span,
}

/// A type as written in a declaration.
#[derive(Clone, Debug, PartialEq)]
pub enum TypeRef {
    /// An elementary type (`BOOL`, `INT`, `TIME`, …), upper-cased.
    Elementary {
        /// The name, upper-cased.
        name: String,
        /// Where.
        span: Span,
    },
    /// A function block or user type.
    Named(Ident),
    /// `ARRAY [a..b, c..d] OF type`.
    Array {
        /// The index ranges.
        ranges: Vec<(Expr, Expr)>,
        /// The element type.
        of: Box<TypeRef>,
        /// Where.
        span: Span,
    },
    /// `STRING` or `STRING[n]` (`WSTRING` too).
    String {
        /// `WSTRING`.
        wide: bool,
        /// The length.
        len: Option<u32>,
        /// Where.
        span: Span,
    },
    /// `INT (0..100)`.
    Subrange {
        /// The base type.
        base: Box<TypeRef>,
        /// The least value.
        low: Expr,
        /// The greatest value.
        high: Expr,
        /// Where.
        span: Span,
    },
    /// `(Red, Green, Blue)`.
    Enum {
        /// The values.
        values: Vec<Ident>,
        /// Where.
        span: Span,
    },
}

/// An initial value.
#[derive(Clone, Debug, PartialEq)]
pub enum Init {
    /// An expression.
    Expr(Expr),
    /// `[1, 2, 3(0)]`.
    Array {
        /// The elements.
        elems: Vec<ArrayInit>,
        /// Where.
        span: Span,
    },
    /// `(IN := TRUE, PT := T#1s)`.
    Struct {
        /// The fields and their values.
        fields: Vec<(Ident, Init)>,
        /// Where.
        span: Span,
    },
}

/// One element of an array initialiser.
#[derive(Clone, Debug, PartialEq)]
pub enum ArrayInit {
    /// A value.
    Value(Init),
    /// `n(value)` or `n()`: the value repeated `n` times.
    Repeat {
        /// How many times.
        count: Expr,
        /// The value (none: the default).
        value: Option<Box<Init>>,
    },
}

/// One declaration of a `TYPE … END_TYPE` block.
#[derive(Clone, Debug, PartialEq)]
pub struct TypeDecl {
    /// The type's name.
    pub name: Ident,
    /// Its definition (an enumeration, a subrange, an array, an alias).
    pub ty: TypeRef,
    /// Its default value.
    pub init: Option<Init>,
    /// From the name to the `;`.
    pub span: Span,
}

/// `CONFIGURATION … END_CONFIGURATION`.
#[derive(Clone, Debug, PartialEq)]
pub struct Configuration {
    /// Its name.
    pub name: Ident,
    /// Its `VAR_GLOBAL` sections.
    pub globals: Vec<VarBlock>,
    /// Its resources (a configuration with tasks and programs directly inside has one
    /// resource with no name).
    pub resources: Vec<Resource>,
    /// Where.
    pub span: Span,
}

/// `RESOURCE name ON cpu … END_RESOURCE`.
#[derive(Clone, Debug, PartialEq)]
pub struct Resource {
    /// Its name and the processor it runs on (none for a configuration's single resource).
    pub name: Option<(Ident, Ident)>,
    /// Its `VAR_GLOBAL` sections.
    pub globals: Vec<VarBlock>,
    /// Its tasks.
    pub tasks: Vec<Task>,
    /// Its program instances.
    pub programs: Vec<ProgramInstance>,
    /// Where.
    pub span: Span,
}

/// `TASK name (INTERVAL := T#20ms, PRIORITY := 1);`
#[derive(Clone, Debug, PartialEq)]
pub struct Task {
    /// Its name.
    pub name: Ident,
    /// Its settings (`SINGLE`, `INTERVAL`, `PRIORITY`), in order.
    pub settings: Vec<(Ident, Expr)>,
    /// Where.
    pub span: Span,
}

/// `PROGRAM inst WITH task : Type (args);`
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramInstance {
    /// The instance's name.
    pub name: Ident,
    /// The task it runs in.
    pub task: Option<Ident>,
    /// The program type.
    pub ty: Ident,
    /// Connections of its inputs and outputs.
    pub args: Vec<Arg>,
    /// Where.
    pub span: Span,
}

/// An expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where (parentheses included).
    pub span: Span,
}

/// What an expression is.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// `TRUE`, `FALSE`, `BOOL#1`… (`BOOL#1` is an [`ExprKind::Int`] with its type).
    Bool(bool),
    /// An integer literal; `ty` the upper-cased type of a typed literal (`INT#5`).
    Int {
        /// The value (negative only in a typed literal: `INT#-5`; `-5` is a negation).
        value: i128,
        /// The type prefix, upper-cased.
        ty: Option<String>,
    },
    /// A real literal as written, without `_` (`1.5E3`, `REAL#2.5`).
    Real(String),
    /// A duration, in microseconds.
    Time(i64),
    /// A string literal, escapes decoded.
    Str(String),
    /// A variable (or an enumerated value).
    Var(Ident),
    /// `of.field` (`T1.Q`).
    Member {
        /// The structure or instance.
        of: Box<Expr>,
        /// The field.
        field: Ident,
    },
    /// `of[i, j]`.
    Index {
        /// The array.
        of: Box<Expr>,
        /// The subscripts.
        index: Vec<Expr>,
    },
    /// A direct address (`%IX0.1`).
    Direct(String),
    /// `NOT e`, `-e`.
    Unary {
        /// The operator.
        op: UnOp,
        /// The operand.
        e: Box<Expr>,
    },
    /// `l op r`.
    Binary {
        /// The operator.
        op: BinOp,
        /// The left operand.
        l: Box<Expr>,
        /// The right operand.
        r: Box<Expr>,
    },
    /// A function call `MAX(a, b)`.
    Call {
        /// The function.
        name: Ident,
        /// The arguments.
        args: Vec<Arg>,
    },
}

/// A unary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    /// `NOT`.
    Not,
    /// `-`.
    Neg,
}

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `OR`.
    Or,
    /// `XOR`.
    Xor,
    /// `AND` or `&`.
    And,
    /// `=`.
    Eq,
    /// `<>`.
    Ne,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `MOD`.
    Mod,
    /// `**`.
    Pow,
}

impl BinOp {
    /// Every operator with its spelling and binding strength (higher binds tighter).
    pub const TABLE: [(BinOp, &'static str, u8); 15] = [
        (BinOp::Or, "OR", 1),
        (BinOp::Xor, "XOR", 2),
        (BinOp::And, "AND", 3),
        (BinOp::Eq, "=", 4),
        (BinOp::Ne, "<>", 4),
        (BinOp::Lt, "<", 5),
        (BinOp::Le, "<=", 5),
        (BinOp::Gt, ">", 5),
        (BinOp::Ge, ">=", 5),
        (BinOp::Add, "+", 6),
        (BinOp::Sub, "-", 6),
        (BinOp::Mul, "*", 7),
        (BinOp::Div, "/", 7),
        (BinOp::Mod, "MOD", 7),
        (BinOp::Pow, "**", 9),
    ];
    /// How the operator is written.
    pub fn symbol(self) -> &'static str {
        BinOp::TABLE.iter().find(|e| e.0 == self).map_or("?", |e| e.1)
    }
    /// How tightly it binds (unary operators bind at 8).
    pub fn precedence(self) -> u8 {
        BinOp::TABLE.iter().find(|e| e.0 == self).map_or(0, |e| e.2)
    }
}

/// The precedence of the unary operators: between `*` and `**`.
pub const UNARY_PRECEDENCE: u8 = 8;

/// An argument of a call.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// A positional argument.
    Positional(Expr),
    /// `IN := x`.
    Input {
        /// The parameter.
        name: Ident,
        /// The value.
        value: Expr,
    },
    /// `Q => y`, `NOT Q => y`.
    Output {
        /// The parameter.
        name: Ident,
        /// `NOT Q => y`.
        negated: bool,
        /// Where the value goes.
        target: Expr,
    },
}

/// A statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where (without the `;`).
    pub span: Span,
}

/// What a statement is.
#[derive(Clone, Debug, PartialEq)]
pub enum StmtKind {
    /// `target := value`.
    Assign {
        /// The variable written.
        target: Expr,
        /// The value.
        value: Expr,
    },
    /// `T1(IN := s, PT := T#5s)`.
    Call {
        /// The instance (a variable, member or array element).
        callee: Expr,
        /// The arguments.
        args: Vec<Arg>,
    },
    /// `IF … ELSIF … ELSE … END_IF`.
    If {
        /// Each condition with its statements.
        branches: Vec<(Expr, Vec<Stmt>)>,
        /// The `ELSE` statements.
        otherwise: Option<Vec<Stmt>>,
    },
    /// `CASE … OF … END_CASE`.
    Case {
        /// The value compared.
        selector: Expr,
        /// The arms.
        arms: Vec<CaseArm>,
        /// The `ELSE` statements.
        otherwise: Option<Vec<Stmt>>,
    },
    /// `FOR var := from TO to BY by DO … END_FOR`.
    For {
        /// The control variable.
        var: Ident,
        /// The first value.
        from: Expr,
        /// The last value.
        to: Expr,
        /// The step.
        by: Option<Expr>,
        /// The statements.
        body: Vec<Stmt>,
    },
    /// `WHILE cond DO … END_WHILE`.
    While {
        /// The condition.
        cond: Expr,
        /// The statements.
        body: Vec<Stmt>,
    },
    /// `REPEAT … UNTIL cond END_REPEAT`.
    Repeat {
        /// The statements.
        body: Vec<Stmt>,
        /// The condition.
        until: Expr,
    },
    /// `EXIT`.
    Exit,
    /// `CONTINUE`.
    Continue,
    /// `RETURN`.
    Return,
    /// A lone `;`.
    Empty,
    /// A property comment `//#ASSERT expr : name` or `(*#ASSERT expr : name*)`.
    Assert(Assertion),
}

/// A property comment's content.
#[derive(Clone, Debug, PartialEq)]
pub struct Assertion {
    /// The property (ST syntax; its span is inside the comment).
    pub expr: Expr,
    /// Its name.
    pub name: Option<Ident>,
    /// The comment's text after `#ASSERT`, trimmed.
    pub text: String,
}

/// One arm of a `CASE`.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseArm {
    /// Its labels.
    pub labels: Vec<CaseLabel>,
    /// Its statements.
    pub body: Vec<Stmt>,
}

/// A `CASE` label.
#[derive(Clone, Debug, PartialEq)]
pub enum CaseLabel {
    /// One value.
    Value(Expr),
    /// `low..high`.
    Range(Expr, Expr),
}

/// One line of an IL body.
#[derive(Clone, Debug, PartialEq)]
pub struct IlLine {
    /// `label:`.
    pub label: Option<Ident>,
    /// The instruction.
    pub instr: IlInstr,
    /// Where.
    pub span: Span,
}

/// An IL instruction.
#[derive(Clone, Debug, PartialEq)]
pub enum IlInstr {
    /// An operator with its operands: `LD x`, `ANDN y`, `ADD 1`, `MAX b`, `AND( … )`.
    Op {
        /// The operator.
        op: IlOp,
        /// The `N` modifier.
        negate: bool,
        /// The `C` modifier.
        cond: bool,
        /// The operands (one for the standard operators; a function's may be several).
        operands: Vec<Expr>,
        /// The lines of `OP( … )`, after the operand on the `(`'s line if any.
        nested: Option<Vec<IlLine>>,
    },
    /// `CAL inst(args)`, `CALC`, `CALCN`.
    Call {
        /// `C`.
        cond: bool,
        /// `N`.
        negate: bool,
        /// The instance.
        instance: Expr,
        /// The arguments.
        args: Vec<Arg>,
    },
    /// `JMP label`, `JMPC`, `JMPCN`.
    Jump {
        /// `C`.
        cond: bool,
        /// `N`.
        negate: bool,
        /// The target.
        label: Ident,
    },
    /// `RET`, `RETC`, `RETCN`.
    Return {
        /// `C`.
        cond: bool,
        /// `N`.
        negate: bool,
    },
    /// A function block input as an operator: `IN T1`, `S1 SR1`, `CU C1`.
    FbOp {
        /// The input, upper-cased.
        op: String,
        /// The instance.
        instance: Expr,
    },
    /// A property comment.
    Assert(Assertion),
    /// A line with only a label.
    Empty,
}

/// An IL operator.
#[derive(Clone, Debug, PartialEq)]
pub enum IlOp {
    /// `LD`.
    Ld,
    /// `ST`.
    St,
    /// `S`.
    S,
    /// `R`.
    R,
    /// `NOT`.
    Not,
    /// A Boolean or arithmetic operator (`AND` also written `&`).
    Bin(BinOp),
    /// A function used as an operator (`MAX b`).
    Function(Ident),
}
