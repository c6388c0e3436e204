use automat_syntax::ast::*;
#[test]
fn sizes() {
    println!("Expr {} ExprKind {} Literal {} LitKind {} Stmt {} StmtKind {} CondBlock {} TypeSpec {} VarDecl {} Initializer {}",
        std::mem::size_of::<Expr>(), std::mem::size_of::<ExprKind>(), std::mem::size_of::<Literal>(), std::mem::size_of::<LitKind>(),
        std::mem::size_of::<Stmt>(), std::mem::size_of::<StmtKind>(), std::mem::size_of::<CondBlock>(), std::mem::size_of::<TypeSpec>(), std::mem::size_of::<VarDecl>(), std::mem::size_of::<Initializer>());
}
