# The two commands of the README, and the targets they stand on.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all deps configure build demo test readme-image format clean

all: build

deps:
	scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	mkdir -p out
	$(BUILD_DIR)/penumbra render scenes/demo.scene -o out/demo.exr -o out/demo.png

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The picture at the top of the README.
readme-image: build
	$(BUILD_DIR)/penumbra render scenes/demo.scene --size 512x512 -o docs/images/demo.png

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD_DIR) out
