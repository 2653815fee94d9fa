module github.com/mcstat/mcstat/bindings/go

go 1.19
