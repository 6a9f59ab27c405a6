// sample.cpp: the input of the function_length_* tests (tools/function-length.py --limit 5):
// two functions over 5 lines (a member, and one holding a lambda), one over 5 lines with a
// reason, and braces inside a raw string, which are not code.
namespace demo {

struct Holder {
    int short_member() const { return 1; }
    int long_member() const {
        int a = 1;
        a *= 2;
        a -= 3;
        return a;
    }
};

// function-length: a fixture of a function with a reason
long justified(long b) {
    b <<= 1;
    b |= 4;
    b ^= 7;
    return b;
}

const char* text() {
    return R"(}}} { not code )";
}

int with_lambda() {
    auto f = [](int x) {
        if (x) { return 1; }
        return 2;
    };
    return f(1) + f(0);
}

}  // namespace demo
